"""The collector's walking policy (reference-facts §5), one action per frame.

A 360° scan (12 turns of 30°), then frontier exploration on a 5 cm obstacle map built from
depth, choosing frontiers with :class:`TargetAwareChooser`. The map decides *where* to go (what
has been seen); the walk to a chosen frontier follows the navigable grid, like the reference's
shortest-path follower, so the kept trajectories are free of collisions. Once the target
itself has been seen (the ground-truth instance image shows enough of it within range), the
shortest path to its nearest view point, then turns until it is straight ahead, then STOP.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.explorer import unexplored_heading
from vlln.agents.frontier.frontiers import ChooserConfig, find_frontiers
from vlln.agents.frontier.mapping import MapConfig, ObstacleMap, Pose
from vlln.agents.frontier.planner import turn_toward
from vlln.datagen.collector.chooser import TargetAwareChooser
from vlln.datagen.collector.lattice import LatticeFollower
from vlln.datagen.collector.visibility import DOWN_TILT, best_central_pixels
from vlln.errors import ConfigError
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.geodesic import GeodesicField
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.world.frame import wrap_angle, yaw_of
from vlln.world.model import ObjectInstance

NOT_FOUND = "target_not_found"  # every frontier visited, target never seen
_STAND_SPREAD = 0.3  # m; how far from a stand point the follower may stop


@dataclass(frozen=True)
class PolicyConfig:
    """Settings of the collector's policy; distances in metres."""

    map: MapConfig = field(default_factory=lambda: MapConfig(cell_size=0.05))
    chooser: ChooserConfig = field(default_factory=ChooserConfig)
    scan_turns: int = 12
    min_frontier_cells: int = 3
    min_pocket_area: float = 1.5  # m²; smaller unexplored pockets are not frontiers
    frontier_reached: float = 0.3  # m; a frontier goal counts as reached this close
    visited_radius: float = 0.5  # m; frontiers this close to a reached goal are not chosen
    frontier_clear_radius: float = 0.25  # m; a frontier is cleared when all around is seen
    goal_timeout: int = 80  # steps after which a frontier goal is chosen afresh
    goal_attempts: int = 8  # frontiers tried in one step before exploration gives up
    seen_pixels: int = 200  # target pixels (640x480) that count as having seen it ...
    seen_range: float = 5.0  # ... when its nearest seen point is this close
    final_pixels: int = 300  # target pixels wanted in the middle of the last frame ...
    relocations: int = 3  # ... else up to this many moves to a view point that shows it
    stand_candidates: int = 40  # view points tried (nearest first) when looking for one

    def __post_init__(self) -> None:
        if self.scan_turns < 0 or self.seen_pixels < 1 or not self.seen_range > 0.0:
            raise ConfigError(
                "scan_turns must be >= 0, seen_pixels >= 1 and seen_range > 0; got "
                f"{self.scan_turns}, {self.seen_pixels}, {self.seen_range}"
            )


class CollectorPolicy:
    """Explores until the target is seen, then walks the shortest path to it and stops."""

    def __init__(
        self,
        sim: Simulator,
        target: ObjectInstance,
        view_points: tuple[tuple[float, float], ...],
        follower: LatticeFollower,
        start: AgentState,
        rng: np.random.Generator,
        config: PolicyConfig | None = None,
    ) -> None:
        self.config = config or PolicyConfig()
        self.sim = sim
        self.target = target
        self.view_points = view_points
        self.follower = follower
        self.rng = rng
        self.turn = sim.config.motion.turn
        self.origin = (start.position[0], start.position[2])
        self.map = ObstacleMap(sim.config.camera, self.config.map)
        self.chooser = TargetAwareChooser(follower.field, self.origin)
        self.map.mark_free_disc(self._pose(start), 0.3)
        self.scan_left = self.config.scan_turns
        self.seen_at: int | None = None  # the frame at which the target was first seen
        self.failure: str | None = None
        self._frames = 0
        self._goal: tuple[float, float] | None = None  # where the frontier is walked to
        self._goal_frontier: tuple[float, float] | None = None  # the frontier itself, world
        self._look_yaw: float | None = None  # heading to face at a reached frontier
        self._looked = False
        self._goal_follower: LatticeFollower | None = None
        self._goal_age = 0
        self._visited: list[tuple[float, float]] = []
        self._previous: tuple[float, float] | None = None  # last choice, map coordinates
        self._tried_stands: set[tuple[float, float]] = set()
        self._relocations = 0

    def act(self, state: AgentState, frame: Frame) -> Action:
        """The action for the frame seen in ``state``."""
        self.map.update(frame.depth, self._pose(state), 0.0)
        if self.seen_at is None and self._sees_target(frame):
            self.seen_at = self._frames
        self._frames += 1
        if self.scan_left > 0:
            self.scan_left -= 1
            return Action.TURN_LEFT
        if self.seen_at is not None:
            return self._approach(state, frame)
        action = self._explore(state)
        if action is None:
            self.failure = NOT_FOUND
            return Action.STOP
        return action

    # ----------------------------------------------------------------- phases
    def _approach(self, state: AgentState, frame: Frame) -> Action:
        """Walk to a view point, face the target, and stop if the view shows it well; else
        move to the nearest view point from which it would be seen in the middle. Where no
        collision-free walk is found, a greedy step (the trajectory is then likely dropped)."""
        action = self.follower.next_action(state)
        if action is None:
            action = self._greedy(self.follower.field).next_action(state)
        if action != Action.STOP:
            return action
        turn = turn_toward(self._facing_error(state.position, state.yaw), self.turn)
        if turn is not None:
            return turn
        cfg = self.config
        down = self.sim.render(AgentState(state.position, state.yaw, DOWN_TILT))
        if best_central_pixels((frame, down), self.target.id) >= cfg.final_pixels:
            return Action.STOP
        if self._relocations >= cfg.relocations:
            return Action.STOP
        stand = self._better_stand(state)
        if stand is None:
            return Action.STOP
        self._relocations += 1
        field_ = self.sim.geodesic_field([stand])
        radius = self.follower.goal_radius
        self.follower = LatticeFollower(self.sim.grid, field_, radius, self.sim.config.motion)
        action = self.follower.next_action(state)
        if action is None:
            action = self._greedy(field_).next_action(state)
        return action

    def _better_stand(self, state: AgentState) -> tuple[float, float] | None:
        """The nearest untried view point, away from here, whose rendered views (from the
        point and from points around it, since the follower stops only near it), facing the
        target with a yaw reachable by whole turns, show enough of it in the middle."""
        x, _, z = state.position
        here = self.sim.geodesic_field([self.sim.grid.snap_point(x, z)])
        options = [
            p
            for p in self.view_points
            if p not in self._tried_stands and math.hypot(p[0] - x, p[1] - z) > _STAND_SPREAD
        ]
        options.sort(key=lambda p: (here.distance(*p), p))
        for point in options[: self.config.stand_candidates]:
            self._tried_stands.add(point)
            if here.distance(*point) < math.inf and self._shows_target_around(point, state):
                return point
        return None

    def _shows_target_around(self, point: tuple[float, float], state: AgentState) -> bool:
        floor_y = state.position[1]
        d = _STAND_SPREAD / 2.0
        for dx, dz in ((0.0, 0.0), (d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d)):  # centre first
            position = (point[0] + dx, floor_y, point[1] + dz)
            yaw = state.yaw
            yaw += self.turn * round(self._facing_error(position, yaw) / self.turn)
            views = tuple(self.sim.render(AgentState(position, yaw, t)) for t in (0.0, DOWN_TILT))
            if best_central_pixels(views, self.target.id) < self.config.final_pixels:
                return False
        return True

    def _facing_error(self, position: tuple[float, float, float], yaw: float) -> float:
        cx, _, cz = self.target.box.center
        return wrap_angle(yaw_of(cx - position[0], cz - position[2]) - yaw)

    def _explore(self, state: AgentState) -> Action | None:
        """The next step toward the current frontier; a new frontier when it is reached, no
        longer a frontier, or taking too long; None when no frontier is left."""
        for _ in range(self.config.goal_attempts):
            needs_goal = self._goal_follower is None or self._goal_done()
            if needs_goal and not self._choose_goal(state):
                return None
            follower = self._goal_follower
            if follower is None:
                return None
            action = follower.next_action(state)
            if action == Action.STOP:
                action = self._look_at_frontier(state)
            if action is not None and action != Action.STOP:
                self._goal_age += 1
                return action
            self._drop_goal()  # reached and looked at, or no collision-free walk to it
        return None

    def _look_at_frontier(self, state: AgentState) -> Action | None:
        """At a reached frontier, turn toward the unexplored cells beside it (walking up to a
        doorway sideways does not show what is behind it); None once facing them."""
        if self._look_yaw is None and not self._looked and self._goal_frontier is not None:
            gx, gz = self._goal_frontier
            point = (gx - self.origin[0], gz - self.origin[1])
            self._look_yaw = unexplored_heading(self.map, self._pose(state), point, self.turn)
            self._looked = True
        if self._look_yaw is not None:
            turn = turn_toward(wrap_angle(self._look_yaw - state.yaw), self.turn)
            if turn is not None:
                return turn
            self._look_yaw = None
        return None

    # ----------------------------------------------------------------- frontiers
    def _goal_done(self) -> bool:
        """Time to choose again: no goal, too long on it, or its frontier has been cleared
        (no unexplored cell left within ``frontier_clear_radius`` of the frontier point)."""
        if self._goal_frontier is None or self._goal_age >= self.config.goal_timeout:
            self._drop_goal()
            return True
        gx, gz = self._goal_frontier
        row, col = self.map.cell_of(gx - self.origin[0], gz - self.origin[1])
        k = math.ceil(self.config.frontier_clear_radius / self.map.cell_size)
        window = self.map.explored[max(row - k, 0) : row + k + 1, max(col - k, 0) : col + k + 1]
        if window.all():
            self._drop_goal()
            return True
        return False

    def _drop_goal(self) -> None:
        """Forget the goal; it and its frontier are not chosen again."""
        self._look_yaw, self._looked = None, False
        if self._goal is not None and self._goal_frontier is not None:
            self._visited += [self._goal, self._goal_frontier]
        self._goal = self._goal_follower = None

    def _choose_goal(self, state: AgentState) -> bool:
        points = self._frontier_points()
        if points.shape[0] == 0:
            return False
        grid = self.sim.grid
        x, _, z = state.position
        here = self.sim.geodesic_field([grid.snap_point(x, z)])
        world = points + np.array(self.origin)
        snapped = [grid.snap_point(float(px), float(pz)) for px, pz in world]
        reach = np.array([here.distance(px, pz) for px, pz in snapped])
        # A frontier whose walkable point is already underfoot cannot be cleared by walking.
        underfoot = reach < self.config.frontier_reached
        for raw, goal, under in zip(world, snapped, underfoot, strict=True):
            if under:
                self._visited += [(float(raw[0]), float(raw[1])), goal]
        reach[underfoot] = np.inf
        index = self.chooser(points, reach, self._previous, self.rng, self.config.chooser)
        if index is None:
            return False
        self._previous = (float(points[index, 0]), float(points[index, 1]))
        self._goal = snapped[index]
        self._goal_frontier = (float(world[index, 0]), float(world[index, 1]))
        field_ = self.sim.geodesic_field([self._goal])
        radius = self.config.frontier_reached
        self._goal_follower = LatticeFollower(grid, field_, radius, self.sim.config.motion)
        self._goal_age = 0
        return True

    def _frontier_points(self) -> NDArray[np.float64]:
        """Frontier points in map coordinates, minus those near goals already visited."""
        cfg = self.config
        box = self.map.box(2)
        explored = self.map.explored[box.r0 : box.r1, box.c0 : box.c1]
        obstacle = self.map.obstacle[box.r0 : box.r1, box.c0 : box.c1]
        pocket = math.ceil(cfg.min_pocket_area / self.map.cell_size**2)
        found = find_frontiers(explored & ~obstacle, explored, cfg.min_frontier_cells, pocket)
        points = np.array(
            [self.map.cell_centre(box.r0 + f.row, box.c0 + f.col) for f in found], np.float64
        ).reshape(-1, 2)
        if self._visited and points.shape[0]:
            visited = np.array(self._visited) - np.array(self.origin)
            gaps = np.hypot(
                points[:, None, 0] - visited[None, :, 0], points[:, None, 1] - visited[None, :, 1]
            )
            points = points[gaps.min(axis=1) > cfg.visited_radius]
        return points

    # ----------------------------------------------------------------- helpers
    def _sees_target(self, frame: Frame) -> bool:
        mine = frame.instance_ids == self.target.id
        count = int(np.count_nonzero(mine))
        if count < self.config.seen_pixels:
            return False
        depth = frame.depth[mine]
        return bool(depth[depth > 0.0].min(initial=math.inf) <= self.config.seen_range)

    def _greedy(self, field_: GeodesicField) -> GreedyFollower:
        radius = self.follower.goal_radius
        return GreedyFollower(self.sim.grid, field_, radius, self.sim.config.motion)

    def _pose(self, state: AgentState) -> Pose:
        x, _, z = state.position
        return Pose(x - self.origin[0], z - self.origin[1], state.yaw)
