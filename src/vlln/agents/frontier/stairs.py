"""Where the stairs on a storey's map lead, and the path that takes them.

The map's stairs layer holds, per cell, the highest and lowest stair point seen there,
measured from the storey's floor. Stair cells well above the floor belong to a flight going
up, cells well below it to one going down (a storey has at most one flight each way). A
flight leads to the storey above (below) when it climbs (drops) more than ``CLIMB_RISE``.

From above, a flight going down shows only its top tread: the steps below it drop away more
steeply than the level camera looks down. Floor-level stair cells away from any flight going
up are therefore the head of a flight down (:func:`stair_heads`), which the agent looks down
from before it takes it.

The way over a flight is a path on the map to its reachable cell farthest from the floor,
continued in a straight line along the flight's axis (found by fitting a plane to the stair
heights), so that the agent steps off its far end onto the other storey's floor, which its
own map has not seen yet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.perception import Detector
from vlln.agents.frontier.planner import DistanceField
from vlln.world.frame import yaw_of

STAIRS_CATEGORY = "stairs"
CLIMB_RISE = 1.0  # m: a flight that climbs or drops more than this leads to another storey
_ON_FLIGHT = 0.05  # m: stair cells this far from the floor are on the flight
_HEAD_LEVEL = 0.3  # m: stair cells this close to the floor are where a flight meets it
_HEAD_CLEAR = 1.0  # m: ... and the head of a flight down this far from any step going up
_EXTENSION = 1.5  # m: the path goes on this far beyond the flight's last cell


class StairsSight:
    """Which of a map's back-projected pixels the detector takes for stairs."""

    def __init__(self, detector: Detector) -> None:
        self.detector = detector
        labels = detector.labels.items()
        self.ids = np.array([i for i, d in labels if d.category == STAIRS_CATEGORY], np.int64)

    @property
    def possible(self) -> bool:
        """Whether the detector knows of any stairs (else the house has one storey)."""
        return self.ids.size > 0

    def pixels(
        self, obstacle_map: ObstacleMap, instance_ids: NDArray[np.int32], depth: NDArray[np.float32]
    ) -> NDArray[np.bool_] | None:
        """The stairs among the pixels the map back-projects; None without stairs."""
        if not self.possible:
            return None
        ids = self.detector.detect(
            obstacle_map.subsample(instance_ids),
            obstacle_map.subsample(depth),
            obstacle_map.pixel_area,
        )
        stairs: NDArray[np.bool_] = np.isin(ids, self.ids)
        return stairs


@dataclass(frozen=True)
class StairExit:
    """A flight on a storey's map: ``direction`` +1 (up) or -1 (down), its cells (flat map
    indices), how far from the floor each reaches, and the unit floor-plan ``axis`` along
    which it leads away from the storey."""

    direction: int
    cells: NDArray[np.intp]
    rise: NDArray[np.float64]
    axis: tuple[float, float]


def stair_exits(obstacle_map: ObstacleMap) -> list[StairExit]:
    """The flights of the map that lead to another storey: up first, then down."""
    stairs = obstacle_map.stairs
    if not stairs.any():
        return []
    flat = np.flatnonzero(stairs)
    exits = []
    for direction, extreme in ((1, obstacle_map.stair_high), (-1, obstacle_map.stair_low)):
        rise = direction * extreme.reshape(-1)[flat].astype(np.float64)
        mine = rise > _ON_FLIGHT
        if not mine.any() or rise[mine].max() <= CLIMB_RISE:
            continue
        cells, heights = flat[mine], rise[mine]
        axis = _axis(obstacle_map, cells, heights)
        if axis is not None:
            exits.append(StairExit(direction, cells, heights, axis))
    return exits


def stair_heads(obstacle_map: ObstacleMap) -> NDArray[np.intp]:
    """Flat indices of the floor-level stair cells that belong to no flight going up."""
    box = obstacle_map.box()
    window = (slice(box.r0, box.r1), slice(box.c0, box.c1))
    stairs = obstacle_map.stairs[window]
    if not stairs.any():
        return np.zeros(0, np.intp)
    high, low = obstacle_map.stair_high[window], obstacle_map.stair_low[window]
    level = stairs & (high <= _HEAD_LEVEL) & (low >= -_HEAD_LEVEL)
    climbing = stairs & (high > _HEAD_LEVEL)
    if climbing.any():
        gap = ndimage.distance_transform_edt(~climbing) * obstacle_map.cell_size
        level &= gap > _HEAD_CLEAR
    rows, cols = np.nonzero(level)
    heads: NDArray[np.intp] = (rows + box.r0) * obstacle_map.shape[1] + cols + box.c0
    return heads


def head_facing(obstacle_map: ObstacleMap, pose: Pose, head: tuple[float, float]) -> float | None:
    """The heading down a flight from its head: across the top tread (the floor-level stair
    cells within 1 m of ``head``, whose longer side runs across the flight), away from the
    agent; None when too few of them are known."""
    heads = stair_heads(obstacle_map)
    x, z = _centres(obstacle_map, heads)
    near = np.hypot(x - head[0], z - head[1]) <= 1.0
    if np.count_nonzero(near) < 4:
        return None
    points = np.stack([x[near], z[near]], axis=1)
    centre = points.mean(axis=0)
    _, vectors = np.linalg.eigh(np.cov((points - centre).T))
    ax, az = vectors[:, 0]  # the direction of least spread: along the flight
    if ax * (centre[0] - pose.x) + az * (centre[1] - pose.z) < 0.0:
        ax, az = -ax, -az
    return yaw_of(float(ax), float(az))


def _axis(
    obstacle_map: ObstacleMap, cells: NDArray[np.intp], rise: NDArray[np.float64]
) -> tuple[float, float] | None:
    """Unit direction in which the rise grows (least-squares plane over the cells)."""
    if cells.size < 3:
        return None
    x, z = _centres(obstacle_map, cells)
    design = np.stack([x, z, np.ones_like(x)], axis=1)
    (a, b, _), *_ = np.linalg.lstsq(design, rise, rcond=None)
    norm = math.hypot(a, b)
    if norm < 1e-6:
        return None
    return float(a / norm), float(b / norm)


def _centres(
    obstacle_map: ObstacleMap, cells: NDArray[np.intp]
) -> tuple[NDArray[np.floating], NDArray[np.floating]]:
    n_cols = obstacle_map.shape[1]
    s, (ox, oz) = obstacle_map.cell_size, obstacle_map.origin
    return ox + (cells % n_cols + 0.5) * s, oz + (cells // n_cols + 0.5) * s


def stairs_path(
    obstacle_map: ObstacleMap, distances: DistanceField, flight: StairExit
) -> list[tuple[float, float]] | None:
    """The path over the flight to the storey it leads to; None when no cell of the flight
    beyond the first steps can be reached."""
    n_cols = obstacle_map.shape[1]
    rows, cols = flight.cells // n_cols, flight.cells % n_cols
    reach = np.array([distances.distance(int(r), int(c)) for r, c in zip(rows, cols, strict=True)])
    usable = np.isfinite(reach) & (flight.rise > CLIMB_RISE / 2.0)
    if not usable.any():
        return None
    # The farthest along the flight, then the nearest to the agent.
    order = np.lexsort((reach, -np.round(flight.rise, 2)))
    best = int(next(i for i in order if usable[i]))
    path = distances.path_to(int(rows[best]), int(cols[best]))
    return path + straight_on(path[-1], flight.axis, obstacle_map.cell_size)


def straight_on(
    start: tuple[float, float], axis: tuple[float, float], spacing: float
) -> list[tuple[float, float]]:
    """Points every ``spacing`` metres along ``axis`` for the next ``_EXTENSION`` metres."""
    along = np.arange(1, math.ceil(_EXTENSION / spacing) + 1) * spacing
    return [(start[0] + axis[0] * a, start[1] + axis[1] * a) for a in along.tolist()]
