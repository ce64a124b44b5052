"""The data-collection frontier rule, which sometimes knows where the target is.

Reference-facts §5: each time a frontier is chosen, with probability ``p_continue`` it is the
one nearest the previous choice, otherwise the one with the smallest geodesic distance to the
target (the very first choice is the nearest one). Choices of the second kind are the moments
a route question can explain, so the chooser keeps a log of every choice and its rule.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.frontiers import ChooserConfig
from vlln.sim.geodesic import GeodesicField
from vlln.sim.storey_field import StoreyField

NEAREST = "nearest"
CONTINUE = "continue"
BEST = "best"


@dataclass(frozen=True)
class Choice:
    rule: str  # NEAREST, CONTINUE or BEST
    point: tuple[float, float]  # the frontier, in world coordinates


class TargetAwareChooser:
    """The frontier rule of data collection, with a ground-truth branch.

    ``offset`` turns the map's coordinates (relative to the start) into world coordinates,
    where ``field`` measures the walk to the target from ``height`` (the floor of the storey
    whose points are offered; unused on one storey).
    """

    def __init__(self, field: GeodesicField | StoreyField, offset: tuple[float, float]) -> None:
        self.field = field
        self.offset = offset
        self.height: float | None = None
        self.choices: list[Choice] = []

    def __call__(
        self,
        points: NDArray[np.float64],
        distances: NDArray[np.float64],
        previous: tuple[float, float] | None,
        rng: np.random.Generator,
        config: ChooserConfig,
    ) -> int | None:
        reachable = np.flatnonzero(np.isfinite(distances))
        if reachable.size == 0:
            return None
        rule, index = NEAREST, int(reachable[np.argmin(distances[reachable])])
        if previous is not None:
            if rng.random() < config.p_continue:
                gaps = np.hypot(
                    points[reachable, 0] - previous[0], points[reachable, 1] - previous[1]
                )
                rule, index = CONTINUE, int(reachable[np.argmin(gaps)])
            else:
                to_target = np.array([self._to_target(points[i]) for i in reachable])
                if np.isfinite(to_target).any():
                    rule, index = BEST, int(reachable[np.argmin(to_target)])
        ox, oz = self.offset
        self.choices.append(
            Choice(rule, (float(points[index, 0]) + ox, float(points[index, 1]) + oz))
        )
        return index

    def log_best(self, point: tuple[float, float, float]) -> None:
        """Log a choice made outside the rule but for the same reason: nearest the target
        (``point`` in world coordinates, ``(x, y, z)``)."""
        self.choices.append(Choice(BEST, (point[0], point[2])))

    def _to_target(self, point: NDArray[np.float64]) -> float:
        x, z = float(point[0]) + self.offset[0], float(point[1]) + self.offset[1]
        return self.field.distance(x, z, self.height)
