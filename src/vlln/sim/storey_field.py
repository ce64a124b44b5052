"""Geodesic distance to a goal set across storeys: :class:`GeodesicField` for :class:`Storeys`.

One multi-source Dijkstra runs over the graph of all storeys (see :mod:`vlln.sim.storeys`)
when an episode starts; later queries are table look-ups. Points carry their height ``y``,
which names their storey; on one storey's plan the same ``(x, z)`` can be two places.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from vlln.errors import NavigationError
from vlln.sim.geodesic import PREFIX_MARGIN, ROUND_UP, goal_distances, pull_string
from vlln.sim.storeys import Point3, Storeys

# A way that rises or falls this much (m) goes up or down stairs.
_CLIMB = 0.3


class StoreyField:
    """Shortest-path distance from every cell of every storey to the nearest goal.

    Goals are ``(x, y, z)``, snapped to the nearest navigable cell of their storey. Cells
    farther than ``limit`` metres from every goal read ``inf`` (see :mod:`vlln.sim.geodesic`).
    """

    def __init__(
        self, storeys: Storeys, goals: Sequence[Sequence[float]], limit: float = math.inf
    ) -> None:
        if len(goals) == 0:
            raise NavigationError("the goal set is empty; pass at least one (x, y, z) goal")
        if any(len(goal) != 3 for goal in goals):
            raise NavigationError(
                "goals in a house with several storeys need their height: pass (x, y, z)"
            )
        self.grid = storeys
        snapped = [storeys.snap_point(float(x), float(y), float(z)) for x, y, z in goals]
        self.goals: list[Point3] = list(dict.fromkeys(snapped))
        sources = sorted({storeys.node(*goal) for goal in self.goals})
        dist, predecessors = goal_distances(storeys.cell_graph(), sources, limit)
        dist.flags.writeable = False
        self._flat = dist  # read by index: see GeodesicField
        self._predecessors: NDArray[np.int32] = predecessors
        self.values: tuple[NDArray[np.float64], ...] = tuple(
            part.reshape(storeys.shape) for part in np.split(dist, len(storeys.grids))
        )

    def distance(self, x: float, z: float, y: float | None = None) -> float:
        """Geodesic distance from ``(x, y, z)`` to the nearest goal; ``inf`` if unreachable."""
        if y is None:
            raise NavigationError(
                "distances in a house with several storeys need the height y of the point"
            )
        storeys = self.grid
        level = storeys.level_of(y)
        grid = storeys.grids[level]
        row, col = grid.world_to_cell(x, z)
        if not grid.in_bounds(row, col):
            return math.inf
        node = storeys.node(x, y, z)
        d = float(self._flat[node])
        if d == math.inf:
            return d
        cx, cy, cz = storeys.node_point(node)
        return d + math.sqrt((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) * ROUND_UP

    def is_reachable(self, x: float, z: float, y: float | None = None) -> bool:
        return self.distance(x, z, y) < math.inf

    def path_nodes(
        self, x: float, y: float, z: float, max_length: float | None = None
    ) -> list[Point3]:
        """Cell centres ``(x, y, z)`` from the point's cell toward the nearest goal (all of
        the way, or the first ``max_length`` metres of it)."""
        if not self.is_reachable(x, z, y):
            raise NavigationError(
                f"no path from ({x:.3f}, {y:.3f}, {z:.3f}) to the goals: the point is off the "
                "navigable area or in a region the goals cannot be reached from"
            )
        storeys = self.grid
        node = storeys.node(x, y, z)
        points = [storeys.node_point(node)]
        travelled = 0.0
        limit = math.inf if max_length is None else max_length
        while self._predecessors[node] >= 0 and travelled < limit:
            node = int(self._predecessors[node])
            point = storeys.node_point(node)
            travelled += math.dist(point, points[-1])
            points.append(point)
        return points

    def shortest_path(
        self, x: float, z: float, max_length: float | None = None, y: float | None = None
    ) -> list[tuple[float, float]]:
        """Floor-plan polyline ``(x, z)`` of the way on the point's storey, up to where it
        leaves that storey's floor (the stairs) or the goal; the rest is :meth:`climb`'s."""
        if y is None:
            raise NavigationError("paths in a house with several storeys need the height y")
        floor = self.grid.floor_ys[self.grid.level_of(y)]
        limit = None if max_length is None else max_length * PREFIX_MARGIN + 1.0
        points = [(x, z)]
        for px, py, pz in self.path_nodes(x, y, z, limit)[1:]:
            if py != floor and y == floor:
                break
            points.append((px, pz))
        return pull_string(self.grid.grid_at(y), points)

    def climb(self, x: float, y: float, z: float, within: float) -> int:
        """+1 when the way to the goals goes up stairs within ``within`` metres, -1 when it
        goes down, 0 when it stays level there (or no goal can be reached)."""
        if not self.is_reachable(x, z, y):
            return 0
        for _, height, _ in self.path_nodes(x, y, z, within):
            if abs(height - y) > _CLIMB:
                return 1 if height > y else -1
        return 0
