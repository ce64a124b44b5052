"""Shortest paths on the agent's own map, and a follower that turns them into actions.

One Dijkstra from the agent over the explored window gives the distance to every cell, which
both ranks frontiers and yields the path to the chosen goal, so a replan costs one search.
Obstacles are inflated by the agent's radius; unexplored cells count as free (the map is
optimistic, and a wrong guess shows up as a new obstacle or a bump that triggers a replan).
Cells near obstacles cost more, which keeps paths off walls and door frames. Stairs that
climb or drop more than a step are left out of paths unless the agent means to take them.

The graph is built from the eight neighbour slots of every cell, row by row, so it takes a few
vectorised array operations and no sorting.
"""

from __future__ import annotations

import math
from typing import Self

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator
from scipy import ndimage, sparse
from scipy.sparse import csgraph

from vlln.agents.frontier.mapping import CellBox, ObstacleMap, Pose
from vlln.config import settings_dataclass
from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.world.frame import wrap_angle, yaw_of

_OFFSETS = ((0, 1), (1, 0), (0, -1), (-1, 0), (1, 1), (1, -1), (-1, 1), (-1, -1))


@settings_dataclass
class PlannerConfig:
    """How the map becomes a graph: obstacle inflation, wall clearance, search window."""

    inflation: float = Field(default=0.18, ge=0.0)
    """obstacle cells closer than this (centre to centre) are blocked"""
    near_wall: float = 0.45  # cells closer than this to an obstacle cost extra
    near_wall_cost: float = Field(default=2.0, ge=1.0)  # cost multiplier of those cells
    escape: float = 0.4  # around the agent only obstacle cells themselves block
    margin: int = 10  # cells around the explored box that the search may use

    @model_validator(mode="after")
    def _inflation_below_near_wall(self) -> Self:
        if not self.inflation < self.near_wall:
            raise ConfigError(f"need inflation < near_wall, got {self.inflation}, {self.near_wall}")
        return self


def _disc(radius_cells: float) -> NDArray[np.bool_]:
    k = math.floor(radius_cells)
    rows, cols = np.mgrid[-k : k + 1, -k : k + 1]
    disc: NDArray[np.bool_] = rows**2 + cols**2 <= radius_cells**2
    return disc


class DistanceField:
    """Distances from the agent to every cell of a map window, with the paths behind them."""

    def __init__(
        self,
        obstacle_map: ObstacleMap,
        box: CellBox,
        traversable: NDArray[np.bool_],
        distances: NDArray[np.float64],
        predecessors: NDArray[np.int32],
    ) -> None:
        self.map = obstacle_map
        self.box = box
        self.traversable = traversable
        self.distances = distances  # (rows, cols) of the window, inf where unreachable
        self._predecessors = predecessors

    def distance(self, row: int, col: int) -> float:
        """Distance to a map cell; inf outside the window or when unreachable."""
        r0, r1, c0, c1 = self.box
        if not (r0 <= row < r1 and c0 <= col < c1):
            return math.inf
        return float(self.distances[row - r0, col - c0])

    def path_to(self, row: int, col: int) -> list[tuple[float, float]]:
        """Cell centres from the agent to a reachable map cell."""
        r0, _, c0, c1 = self.box
        width = c1 - c0
        node = (row - r0) * width + (col - c0)
        chain = [node]
        while self._predecessors[node] >= 0:
            node = int(self._predecessors[node])
            chain.append(node)
        chain.reverse()
        return [self.map.cell_centre(r0 + n // width, c0 + n % width) for n in chain]


class Planner:
    """Builds :class:`DistanceField` s on an :class:`ObstacleMap`."""

    def __init__(self, config: PlannerConfig | None = None) -> None:
        self.config = config or PlannerConfig()

    def plan(
        self, obstacle_map: ObstacleMap, pose: Pose, over_stairs: bool = False
    ) -> DistanceField:
        """Distances from the agent over the explored window (plus a margin); paths go up or
        down stairs only ``over_stairs``."""
        cfg = self.config
        s = obstacle_map.cell_size
        row, col = obstacle_map.cell_of(pose.x, pose.z)
        box = obstacle_map.box(cfg.margin)
        box = CellBox(
            min(box.r0, max(row - 1, 0)),
            max(box.r1, row + 2),
            min(box.c0, max(col - 1, 0)),
            max(box.c1, col + 2),
        )
        obstacle = obstacle_map.obstacle[box.r0 : box.r1, box.c0 : box.c1]
        blocked = ndimage.maximum_filter(obstacle, footprint=_disc(cfg.inflation / s))
        if not over_stairs:
            blocked |= obstacle_map.steep_window(box)
        # The extra cost near walls is a soft preference: a square neighbourhood will do.
        near = ndimage.maximum_filter(obstacle, size=2 * math.floor(cfg.near_wall / s) + 1)
        local_r, local_c = row - box.r0, col - box.c0
        # The agent stands where it stands: let it walk out of the inflated margin around it
        # (an obstacle seen a little too close must not seal it in), but not through obstacles.
        k = math.ceil(cfg.escape / s)
        r0, c0 = max(local_r - k, 0), max(local_c - k, 0)
        near_agent = blocked[r0 : local_r + k + 1, c0 : local_c + k + 1]
        pr, pc = np.ogrid[
            r0 - local_r : r0 - local_r + near_agent.shape[0],
            c0 - local_c : c0 - local_c + near_agent.shape[1],
        ]
        inside = (pr * pr + pc * pc) * s * s <= cfg.escape**2
        near_agent[inside & ~obstacle[r0 : local_r + k + 1, c0 : local_c + k + 1]] = False
        blocked[local_r, local_c] = False
        traversable = ~blocked
        cost = np.where(near, cfg.near_wall_cost, 1.0) * s
        graph = _grid_graph(traversable, cost)
        rows, cols = traversable.shape
        distances, predecessors = csgraph.dijkstra(
            graph, directed=True, indices=local_r * cols + local_c, return_predecessors=True
        )
        return DistanceField(
            obstacle_map, box, traversable, distances.reshape(rows, cols), predecessors
        )


def _grid_graph(traversable: NDArray[np.bool_], cost: NDArray[np.float64]) -> sparse.csr_matrix:
    """Eight-neighbour graph between traversable cells; a move costs its length times the
    mean cost of its two cells, and a diagonal move needs both side cells free.

    Every cell's eight neighbour slots are laid out row by row and the blocked ones dropped,
    which yields the CSR arrays directly, without sorting."""
    rows, cols = traversable.shape
    n = rows * cols
    padded = np.zeros((rows + 2, cols + 2), bool)
    padded[1:-1, 1:-1] = traversable
    padded_cost = np.ones((rows + 2, cols + 2))
    padded_cost[1:-1, 1:-1] = cost
    node = np.arange(n, dtype=np.int32).reshape(rows, cols)
    usable = np.empty((rows, cols, 8), bool)
    targets = np.empty((rows, cols, 8), np.int32)
    weights = np.empty((rows, cols, 8))
    for k, (dr, dc) in enumerate(_OFFSETS):
        ok = traversable & padded[1 + dr : 1 + dr + rows, 1 + dc : 1 + dc + cols]
        if dr and dc:
            ok &= padded[1 + dr : 1 + dr + rows, 1 : 1 + cols]
            ok &= padded[1 : 1 + rows, 1 + dc : 1 + dc + cols]
        usable[:, :, k] = ok
        targets[:, :, k] = node + np.int32(dr * cols + dc)
        neighbour_cost = padded_cost[1 + dr : 1 + dr + rows, 1 + dc : 1 + dc + cols]
        weights[:, :, k] = (0.5 * math.hypot(dr, dc)) * (cost + neighbour_cost)
    usable_flat = usable.reshape(-1)
    indptr = np.zeros(n + 1, np.int32)
    np.cumsum(usable.reshape(n, 8).sum(axis=1), out=indptr[1:])
    return sparse.csr_matrix(
        (weights.reshape(-1)[usable_flat], targets.reshape(-1)[usable_flat], indptr),
        shape=(n, n),
    )


class PathFollower:
    """Pure pursuit with whole turns: aim at the path point ``lookahead`` metres ahead, turn
    while it is more than half a turn off the heading, else step forward."""

    def __init__(
        self,
        path: list[tuple[float, float]],
        turn: float,
        lookahead: float = 0.6,
        tolerance: float = 0.25,
    ) -> None:
        if not path:
            raise ConfigError("a path needs at least one point")
        self.path = np.asarray(path, np.float64)
        self.turn = turn
        self.lookahead = lookahead
        self.tolerance = tolerance
        self._index = 0

    @property
    def goal(self) -> tuple[float, float]:
        return float(self.path[-1, 0]), float(self.path[-1, 1])

    def remaining(self) -> NDArray[np.float64]:
        return self.path[self._index :]

    def next_action(self, pose: Pose) -> Action | None:
        """The next move, or None when the end of the path is within ``tolerance``."""
        gx, gz = self.goal
        if math.hypot(gx - pose.x, gz - pose.z) < self.tolerance:
            return None
        window = self.path[self._index : self._index + 40]
        gaps = np.hypot(window[:, 0] - pose.x, window[:, 1] - pose.z)
        self._index += int(np.argmin(gaps))
        ahead = self.path[self._index :]
        far = np.hypot(ahead[:, 0] - pose.x, ahead[:, 1] - pose.z) >= self.lookahead
        target = ahead[int(np.argmax(far))] if far.any() else ahead[-1]
        error = wrap_angle(yaw_of(target[0] - pose.x, target[1] - pose.z) - pose.yaw)
        return turn_toward(error, self.turn) or Action.MOVE_FORWARD


def turn_toward(error: float, turn: float) -> Action | None:
    """The turn that reduces a heading error (left positive), None within half a turn."""
    if abs(error) <= turn / 2.0 + 1e-6:
        return None
    return Action.TURN_LEFT if error > 0.0 else Action.TURN_RIGHT
