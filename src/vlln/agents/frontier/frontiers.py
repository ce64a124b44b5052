"""Frontiers (where explored free space meets the unexplored) and the rule that picks one.

A frontier is a connected run of explored free cells that touch unexplored cells; it is
represented by its member nearest its centroid, a cell the agent can walk to. Unexplored
pockets smaller than a room corner (1.5 m² by default) are not worth a trip and are ignored,
and so are runs of only a few cells.

The choice follows the reference's data collection: the first frontier is the nearest one;
after that, with probability ``p_continue`` the frontier nearest the previous choice (so the
agent finishes one region before leaving it), otherwise the one nearest the agent. A route
hint from the oracle overrides both: the nearest frontier within a cone around the hinted
direction wins when there is one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from pydantic import Field
from scipy import ndimage

from vlln.config import settings_dataclass
from vlln.errors import ConfigError
from vlln.world.frame import wrap_angle, yaw_of

_FOUR = ndimage.generate_binary_structure(2, 1)
_EIGHT = ndimage.generate_binary_structure(2, 2)


@dataclass(frozen=True)
class Frontier:
    """One frontier: its representative cell (row, col) and its length in cells."""

    row: int
    col: int
    size: int


def find_frontiers(
    free: NDArray[np.bool_],
    explored: NDArray[np.bool_],
    min_cells: int = 3,
    min_pocket_cells: int = 150,
) -> list[Frontier]:
    """Frontiers of a map window, largest first (ties by position).

    ``free``: cells the agent may stand on (explored, not an obstacle, not too close to one);
    ``explored``: cells the camera has covered. Unexplored regions that touch the window's
    border are never treated as pockets, since they may continue outside it.
    """
    if free.shape != explored.shape or free.ndim != 2:
        raise ConfigError(f"free {free.shape} and explored {explored.shape} must be equal 2-D")
    unexplored = ~explored
    labels, count = ndimage.label(unexplored, structure=_FOUR)
    if count == 0:
        return []
    sizes = np.bincount(labels.ravel(), minlength=count + 1)
    border = np.unique(np.concatenate([labels[0], labels[-1], labels[:, 0], labels[:, -1]]))
    large = sizes >= min_pocket_cells
    large[border] = True
    large[0] = False
    open_unexplored = large[labels]
    touching = ndimage.binary_dilation(open_unexplored, structure=_FOUR)
    cells = free & touching
    runs, n_runs = ndimage.label(cells, structure=_EIGHT)
    if n_runs == 0:
        return []
    rows, cols = np.nonzero(runs)
    run_of = runs[rows, cols]
    counts = np.bincount(run_of, minlength=n_runs + 1)
    centre_r = np.bincount(run_of, weights=rows, minlength=n_runs + 1)[run_of] / counts[run_of]
    centre_c = np.bincount(run_of, weights=cols, minlength=n_runs + 1)[run_of] / counts[run_of]
    offset = (rows - centre_r) ** 2 + (cols - centre_c) ** 2
    order = np.lexsort((offset, run_of))
    first = order[np.r_[True, run_of[order][1:] != run_of[order][:-1]]]
    found = [
        Frontier(int(rows[i]), int(cols[i]), int(counts[run_of[i]]))
        for i in first
        if counts[run_of[i]] >= min_cells
    ]
    found.sort(key=lambda f: (-f.size, f.row, f.col))
    return found


@settings_dataclass
class ChooserConfig:
    """The frontier choice rule's two knobs."""

    p_continue: float = Field(default=0.9, ge=0.0, le=1.0)
    """chance of the frontier nearest the previous one"""
    hint_cone_deg: float = Field(default=50.0, gt=0.0, le=180.0)
    """half-width of the cone around a hinted direction"""


def choose_frontier(
    points: NDArray[np.float64],
    distances: NDArray[np.float64],
    agent: tuple[float, float],
    previous: tuple[float, float] | None,
    hint: float | None,
    rng: np.random.Generator,
    config: ChooserConfig,
) -> int | None:
    """Index of the chosen frontier, or None when none is reachable.

    ``points``: (n, 2) floor-plan positions; ``distances``: geodesic distance from the agent
    (inf when unreachable); ``hint``: a yaw the oracle pointed to, if any.
    """
    reachable = np.flatnonzero(np.isfinite(distances))
    if reachable.size == 0:
        return None
    nearest = int(reachable[np.argmin(distances[reachable])])
    if hint is not None:
        bearings = [yaw_of(points[i, 0] - agent[0], points[i, 1] - agent[1]) for i in reachable]
        off = np.array([abs(wrap_angle(b - hint)) for b in bearings])
        inside = reachable[off <= math.radians(config.hint_cone_deg)]
        if inside.size:
            return int(inside[np.argmin(distances[inside])])
    if previous is None:
        return nearest
    if rng.random() < config.p_continue:
        gaps = np.hypot(points[reachable, 0] - previous[0], points[reachable, 1] - previous[1])
        return int(reachable[np.argmin(gaps)])
    return nearest
