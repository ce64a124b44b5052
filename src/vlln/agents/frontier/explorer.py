"""Where to walk next: frontier goals while searching, a spot beside a candidate once found.

The explorer owns the current goal and its path. It replans only when it must: a new goal, a
path that new obstacles cut, a bump, the end of the path, or every ``replan_interval`` steps
to pick up what the map has learnt meanwhile. Between replans a step costs one pure-pursuit
look-up, which keeps the per-step cost of the agent far below the cost of rendering a frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import field

import numpy as np
from numpy.typing import NDArray
from pydantic import Field
from scipy import ndimage

from vlln.agents.frontier.detector import Candidate
from vlln.agents.frontier.frontiers import ChooserConfig, choose_frontier, find_frontiers
from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.planner import (
    DistanceField,
    PathFollower,
    Planner,
    PlannerConfig,
    turn_toward,
)
from vlln.config import Count, settings_dataclass
from vlln.sim.agent import Action
from vlln.world.frame import heading_vector, wrap_angle

_FOUR = ndimage.generate_binary_structure(2, 1)

FrontierRanker = Callable[[NDArray[np.float64], NDArray[np.float64], Pose], int | None]
"""Picks a frontier instead of the default rule: (points (n, 2), geodesic distances, pose) ->
an index, or None when none is reachable."""


@settings_dataclass
class ExplorerConfig:
    """Frontier filtering and choice, replanning, and how close counts as arrived."""

    planner: PlannerConfig = field(default_factory=PlannerConfig)
    chooser: ChooserConfig = field(default_factory=ChooserConfig)
    replan_interval: Count = 20  # steps between routine replans
    min_frontier_cells: int = 3
    min_pocket_area: float = 1.5  # m²; smaller unexplored pockets are not frontiers
    blacklist_radius: float = 0.5  # frontiers this close to a failed goal are skipped
    approach_radii: tuple[float, ...] = Field(default=(0.3, 0.5, 0.8, 1.2, 2.0, 3.0), min_length=1)
    """tried in turn"""
    frontier_tolerance: float = 0.3  # a frontier counts as reached this close
    candidate_tolerance: float = 0.2


class Explorer:
    """Goal selection, planning and path following on one :class:`ObstacleMap`."""

    def __init__(
        self,
        obstacle_map: ObstacleMap,
        turn: float,
        rng: np.random.Generator,
        config: ExplorerConfig | None = None,
    ) -> None:
        self.map = obstacle_map
        self.turn = turn
        self.rng = rng
        self.config = config or ExplorerConfig()
        self.planner = Planner(self.config.planner)
        self.unreachable: set[int] = set()
        self._blacklist: list[tuple[float, float]] = []
        # The current goal: a frontier point or a candidate id (never both), and its path.
        self._frontier: tuple[float, float] | None = None
        self._candidate: int | None = None
        self._previous_frontier: tuple[float, float] | None = None
        self._follower: PathFollower | None = None
        self._facing: float | None = None  # yaw to turn to at a frontier that is still one
        self._since_plan = 0
        self.look_down = False  # look down at a frontier before giving it up (see step)
        self.rank: FrontierRanker | None = None  # another frontier choice (a hint still wins)
        self._looked_down = False
        self._look_heading: float | None = None
        self.replans = 0  # searches run so far, for profiling

    # ----------------------------------------------------------------- events
    def drop_path(self) -> None:
        """Replan at the next step (a bump, a new hint)."""
        self._follower = None
        self._facing = None

    def give_up_goal(self) -> None:
        """The current goal cannot be reached: never choose it (or what is near it) again."""
        if self._frontier is not None:
            self._blacklist.append(self._frontier)
        if self._candidate is not None:
            self.unreachable.add(self._candidate)
        self._frontier = self._candidate = None
        self._follower = None

    def note_obstacles(self, new_cells: NDArray[np.intp]) -> None:
        """Drop the path if newly seen obstacles come within the inflation radius of it."""
        if self._follower is None or new_cells.size == 0:
            return
        ahead = self._follower.remaining()[:40]
        n_cols = self.map.shape[1]
        s, (ox, oz) = self.map.cell_size, self.map.origin
        x = ox + (new_cells % n_cols + 0.5) * s
        z = oz + (new_cells // n_cols + 0.5) * s
        gaps = np.hypot(ahead[:, None, 0] - x[None, :], ahead[:, None, 1] - z[None, :])
        if gaps.size and gaps.min() <= self.config.planner.inflation:
            self._follower = None

    # ----------------------------------------------------------------- exploring
    def step(self, pose: Pose, hint: float | None) -> Action | None:
        """The next move toward a frontier; None when no frontier is left to reach.

        At a frontier that is still one, the agent first turns toward the unexplored cells
        next to it (the camera sees no floor within 2 m, so walking up to a doorway sideways
        does not reveal what is behind it); only if that does not clear it is it given up.
        With :attr:`look_down`, it then faces the unexplored pocket there and looks down once
        before giving up: the pocket may be the way down a flight of stairs, whose steps a level
        camera cannot see.
        """
        if self._look_heading is not None:
            return self._look_first(pose)
        if self._facing is not None:
            turn = turn_toward(wrap_angle(self._facing - pose.yaw), self.turn)
            if turn is not None:
                return turn
            self._facing = None
            look = self._look_first(pose)
            if look is not None:
                return look
            self.give_up_goal()
        for _ in range(2):
            follower = self._follower
            if follower is None or self._needs_frontier():
                follower = self._choose_frontier(pose, hint)
                if follower is None:
                    return None
            action = follower.next_action(pose)
            self._since_plan += 1
            if action is not None:
                return action
            facing = self._unexplored_direction(pose, follower.goal)
            turn = None if facing is None else turn_toward(wrap_angle(facing - pose.yaw), self.turn)
            if turn is not None:
                self._facing = facing
                return turn
            look = self._look_first(pose)
            if look is not None:
                return look
            self.give_up_goal()
        return None

    def _look_first(self, pose: Pose) -> Action | None:
        """Before the current goal is given up: a turn toward the unexplored pocket next to
        it, then a look down (once per goal); None to give it up now."""
        if self._look_heading is not None:
            turn = turn_toward(wrap_angle(self._look_heading - pose.yaw), self.turn)
            if turn is not None:
                return turn
            self._look_heading = None
            return Action.LOOK_DOWN
        goal = self._frontier
        if not self.look_down or self._looked_down or goal is None:
            return None
        self._looked_down = True
        self._look_heading = look_heading(self.map, pose, self.turn)
        if self._look_heading is None:
            return Action.LOOK_DOWN
        return self._look_first(pose)

    def _unexplored_direction(self, pose: Pose, point: tuple[float, float]) -> float | None:
        return unexplored_heading(self.map, pose, point, self.turn)

    def _needs_frontier(self) -> bool:
        point = self._frontier
        if point is None or self._since_plan >= self.config.replan_interval:
            return True
        row, col = self.map.cell_of(*point)
        window = self.map.explored[max(row - 1, 0) : row + 2, max(col - 1, 0) : col + 2]
        return bool(window.all())  # explored all around: it is no longer a frontier

    def _choose_frontier(self, pose: Pose, hint: float | None) -> PathFollower | None:
        cfg = self.config
        distances = self._plan(pose)
        box = distances.box
        explored = self.map.explored[box.r0 : box.r1, box.c0 : box.c1]
        obstacle = self.map.obstacle[box.r0 : box.r1, box.c0 : box.c1]
        free = distances.traversable & explored & ~obstacle
        free &= ~self.map.stairs[box.r0 : box.r1, box.c0 : box.c1]  # stairs lead elsewhere
        self._exclude_blacklisted(free, box.r0, box.c0)
        pocket = math.ceil(cfg.min_pocket_area / self.map.cell_size**2)
        frontiers = find_frontiers(free, explored, cfg.min_frontier_cells, pocket)
        if not frontiers:
            return None
        cells = [(box.r0 + f.row, box.c0 + f.col) for f in frontiers]
        points = np.array([self.map.cell_centre(r, c) for r, c in cells])
        reach = np.array([distances.distance(r, c) for r, c in cells])
        if self.rank is not None and hint is None:
            index = self.rank(points, reach, pose)
        else:
            index = choose_frontier(
                points,
                reach,
                (pose.x, pose.z),
                self._previous_frontier,
                hint,
                self.rng,
                cfg.chooser,
            )
        if index is None:
            return None
        point = (float(points[index, 0]), float(points[index, 1]))
        self._previous_frontier = point
        follower = self._set_path(distances, cells[index], cfg.frontier_tolerance)
        self._frontier = point
        return follower

    def _exclude_blacklisted(self, free: NDArray[np.bool_], r0: int, c0: int) -> None:
        """Clear the cells around given-up goals, so the rest of a long frontier survives
        with a new representative instead of being dropped with them."""
        s = self.map.cell_size
        k = math.ceil(self.config.blacklist_radius / s)
        rows, cols = free.shape
        for x, z in self._blacklist:
            row, col = self.map.cell_of(x, z)
            row, col = row - r0, col - c0
            lo_r, lo_c = max(row - k, 0), max(col - k, 0)
            patch = free[lo_r : min(row + k + 1, rows), lo_c : min(col + k + 1, cols)]
            if patch.size == 0:
                continue
            pr, pc = np.ogrid[
                lo_r - row : lo_r - row + patch.shape[0], lo_c - col : lo_c - col + patch.shape[1]
            ]
            patch[(pr * pr + pc * pc) * s * s <= self.config.blacklist_radius**2] = False

    # ----------------------------------------------------------------- approaching
    def approach(self, candidate: Candidate, pose: Pose) -> Action | None:
        """The next move toward the reachable spot nearest the candidate; None once there, or
        when no spot near it can be reached (it is then in :attr:`unreachable`)."""
        key = candidate.instance_id
        follower = self._follower
        if (
            follower is None
            or self._candidate != key
            or self._since_plan >= self.config.replan_interval
        ):
            distances = self._plan(pose)
            cell = self._approach_cell(candidate, distances)
            if cell is None:
                self.unreachable.add(key)
                self._follower = None
                return None
            follower = self._set_path(distances, cell, self.config.candidate_tolerance)
            self._candidate = key
        self._since_plan += 1
        return follower.next_action(pose)

    def _approach_cell(
        self, candidate: Candidate, distances: DistanceField
    ) -> tuple[int, int] | None:
        """The nearest reachable cell within the smallest radius of the object that has one."""
        n_cols = self.map.shape[1]
        rows, cols = candidate.cells // n_cols, candidate.cells % n_cols
        s = self.map.cell_size
        reach = math.ceil(max(self.config.approach_radii) / s) + 1
        box = distances.box
        r0, r1 = max(int(rows.min()) - reach, box.r0), min(int(rows.max()) + reach + 1, box.r1)
        c0, c1 = max(int(cols.min()) - reach, box.c0), min(int(cols.max()) + reach + 1, box.c1)
        if r0 >= r1 or c0 >= c1:
            return None
        mask = np.ones((r1 - r0, c1 - c0), bool)
        inside = (rows >= r0) & (rows < r1) & (cols >= c0) & (cols < c1)
        mask[rows[inside] - r0, cols[inside] - c0] = False
        gap = ndimage.distance_transform_edt(mask) * s
        cost = distances.distances[r0 - box.r0 : r1 - box.r0, c0 - box.c0 : c1 - box.c0]
        for radius in self.config.approach_radii:
            options = np.where((gap <= radius) & np.isfinite(cost), cost, np.inf)
            best = int(np.argmin(options))
            if np.isfinite(options.flat[best]):
                return r0 + best // (c1 - c0), c0 + best % (c1 - c0)
        return None

    # ----------------------------------------------------------------- internals
    def _plan(self, pose: Pose, over_stairs: bool = False) -> DistanceField:
        self.replans += 1
        return self.planner.plan(self.map, pose, over_stairs)

    def stairs_distances(self, pose: Pose) -> DistanceField:
        """Distances from the agent with paths over stairs allowed (to take them)."""
        self.drop_path()
        self._frontier = self._candidate = None
        return self._plan(pose, over_stairs=True)

    def _set_path(
        self, distances: DistanceField, cell: tuple[int, int], tolerance: float
    ) -> PathFollower:
        """Follow the path to a cell from now on (the caller records what the goal is)."""
        self._follower = PathFollower(distances.path_to(*cell), self.turn, tolerance=tolerance)
        self._frontier = self._candidate = None
        self._since_plan = 0
        self._looked_down = False
        self._look_heading = None
        return self._follower


def unexplored_heading(
    obstacle_map: ObstacleMap, pose: Pose, point: tuple[float, float], turn: float
) -> float | None:
    """The whole-turn heading from the agent that faces the most unexplored cells within
    1 m of a point that border explored free space (cells behind walls do not count).
    The most common heading, not the mean: in a doorway to a corridor the unexplored lies
    both left and right, and their mean would face the wall opposite."""
    row, col = obstacle_map.cell_of(*point)
    k = math.ceil(1.0 / obstacle_map.cell_size)
    r0, c0 = max(row - k, 0), max(col - k, 0)
    explored = obstacle_map.explored[r0 : row + k + 1, c0 : col + k + 1]
    free = explored & ~obstacle_map.obstacle[r0 : row + k + 1, c0 : col + k + 1]
    open_edge = ~explored & ndimage.binary_dilation(free, structure=_FOUR)
    rows, cols = np.nonzero(open_edge)
    if rows.size == 0:
        return None
    s, (ox, oz) = obstacle_map.cell_size, obstacle_map.origin
    x = ox + (c0 + cols + 0.5) * s - pose.x
    z = oz + (r0 + rows + 0.5) * s - pose.z
    turns = np.round((np.arctan2(-x, -z) - pose.yaw) / turn).astype(int)
    headings = round(2.0 * math.pi / turn)
    counts = np.bincount(turns % headings, minlength=headings)
    best = int(np.argmax(counts))
    return pose.yaw + best * turn


def look_heading(obstacle_map: ObstacleMap, pose: Pose, turn: float) -> float | None:
    """The whole-turn heading along which the agent's line of sight runs longest over
    unexplored cells (from 0.3 to 2 m, up to the first obstacle); None when every one is
    explored or blocked. Unexplored floor next to a wall is short; a hole in the floor is not."""
    headings = round(2.0 * math.pi / turn)
    steps = np.arange(0.3, 2.0, obstacle_map.cell_size)
    best, best_count = None, 0
    for k in sorted(range(headings), key=lambda k: min(k, headings - k)):
        yaw = pose.yaw + k * turn
        dx, dz = heading_vector(yaw)
        count = 0
        for distance in steps:
            row, col = obstacle_map.cell_of(pose.x + dx * distance, pose.z + dz * distance)
            if obstacle_map.obstacle[row, col]:
                break
            count += int(not obstacle_map.explored[row, col])
        if count > best_count:
            best, best_count = yaw, count
    return best
