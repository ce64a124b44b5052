"""The collector's walking policy (docs/reference-facts.md §5), one action per frame.

A 360° scan (12 turns of 30°), then frontier exploration on a 5 cm obstacle map built from
depth, choosing frontiers with :class:`TargetAwareChooser`. The map decides *where* to go (what
has been seen); the walk to a chosen frontier follows the navigable grid, like the reference's
shortest-path follower, so the kept trajectories are free of collisions. Once the target
itself has been seen (the ground-truth instance image shows enough of it within range), the
shortest path to its nearest view point, then turns until it is straight ahead, then STOP.
On ObjectNav any instance of the category is a goal (``others``): the first one seen becomes
the target. With ``explore`` off (the shortest-path strategy) there is no scan and no
exploration: the target counts as seen from the first frame, so the walk is the shortest path
to its nearest view point, the turns to face it, and STOP.

In a house with several storeys each storey has its own map. A flight of stairs whose landing
the map of the agent's storey shows, and which leads toward the target (privileged, like the
chooser's ground-truth branch), is taken at once and logged as a choice of the frontier
nearest the target, so a route question may explain it ("it is upstairs, take the stairs").
Walking to it climbs (or descends) to the landing at its other end, where a first visit to a
storey begins with a partial scan. Flights leading away from the target are offered to the
chooser only once the storey has no frontier left.
"""

from __future__ import annotations

import math
from dataclasses import field

import numpy as np
from pydantic import Field

from vlln.agents.frontier.explorer import unexplored_heading
from vlln.agents.frontier.frontiers import ChooserConfig
from vlln.agents.frontier.mapping import MapConfig
from vlln.agents.frontier.planner import turn_toward
from vlln.config import Count, Positive, settings_dataclass
from vlln.datagen.collector.chooser import TargetAwareChooser
from vlln.datagen.collector.ground import Ground
from vlln.datagen.collector.lattice import LatticeFollower
from vlln.datagen.collector.stairs import Flight, FlightChoices, house_flights
from vlln.datagen.collector.storey_maps import StoreyMaps
from vlln.datagen.collector.visibility import DOWN_TILT, best_central_pixels
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.geodesic import GeodesicField
from vlln.sim.renderer import Frame
from vlln.sim.storey_field import StoreyField
from vlln.sim.storeys import Point3
from vlln.world.frame import wrap_angle, yaw_of
from vlln.world.model import ObjectInstance

NOT_FOUND = "target_not_found"  # every frontier visited, target never seen
_STAND_SPREAD = 0.3  # m; how far from a stand point the follower may stop
# Turns looking round on reaching a storey for the first time; with the turns that then face
# a frontier (at most half a circle) they stay within the filter's run of 13 turns.
_ARRIVAL_SCAN_TURNS = 7


@settings_dataclass
class PolicyConfig:
    """Settings of the collector's policy; distances in metres."""

    map: MapConfig = field(default_factory=lambda: MapConfig(cell_size=0.05))
    chooser: ChooserConfig = field(default_factory=ChooserConfig)
    scan_turns: int = Field(default=12, ge=0)
    min_frontier_cells: int = 3
    min_pocket_area: float = 1.5  # m²; smaller unexplored pockets are not frontiers
    frontier_reached: float = 0.3  # m; a frontier goal counts as reached this close
    visited_radius: float = 0.5  # m; frontiers this close to a reached goal are not chosen
    frontier_clear_radius: float = 0.25  # m; a frontier is cleared when all around is seen
    goal_timeout: int = 80  # steps after which a frontier goal is chosen afresh
    goal_attempts: int = 8  # frontiers tried in one step before exploration gives up
    seen_pixels: Count = 200  # target pixels (640x480) that count as having seen it ...
    seen_range: Positive = 5.0  # ... when its nearest seen point is this close
    final_pixels: int = 300  # target pixels wanted in the middle of the last frame ...
    relocations: int = 3  # ... else up to this many moves to a view point that shows it
    stand_candidates: int = 40  # view points tried (nearest first) when looking for one


class CollectorPolicy:
    """Explores until the target is seen, then walks the shortest path to it and stops."""

    def __init__(
        self,
        ground: Ground,
        target: ObjectInstance,
        view_points: tuple[Point3, ...],
        follower: LatticeFollower,
        start: AgentState,
        rng: np.random.Generator,
        config: PolicyConfig | None = None,
        others: tuple[tuple[ObjectInstance, tuple[Point3, ...]], ...] = (),
        explore: bool = True,
    ) -> None:
        self.config = config or PolicyConfig()
        self.others = others  # every goal with its view points, where any instance will do
        self.ground = ground
        self.sim = ground.sim
        self.target = target
        self.view_points = view_points
        self.follower = follower
        self.rng = rng
        self.turn = self.sim.config.motion.turn
        self.origin = (start.position[0], start.position[2])
        self.maps = StoreyMaps(self.sim.config.camera, self.config.map, self.origin)
        self.chooser = TargetAwareChooser(follower.field, self.origin)
        start_level = ground.level(start.position[1])
        self.maps.of(start_level, start)
        self.scan_left = self.config.scan_turns if explore else 0
        self._scan_turn = Action.TURN_LEFT
        # the frame at which the target was first seen (without exploring: known from the start)
        self.seen_at: int | None = None if explore else 0
        self.failure: str | None = None
        self._frames = 0
        self._goal: Point3 | None = None  # where the frontier is walked to
        self._goal_frontier: tuple[float, float] | None = None  # the frontier itself, world
        self._goal_level = start_level  # the storey of the goal's frontier
        self._goal_flight: Flight | None = None  # set when the goal is a flight's far end
        self._look_yaw: float | None = None  # heading to face at a reached frontier
        self._looked = False
        self._goal_follower: LatticeFollower | None = None
        self._goal_age = 0
        self._previous: tuple[float, float] | None = None  # last choice, map coordinates
        self._tried_stands: set[Point3] = set()
        self._relocations = 0
        storeys, target_field = ground.storeys, follower.field
        self.stairs = FlightChoices(
            house_flights(self.sim.house, storeys) if storeys is not None else [],
            start_level,
            lambda point: ground.distance(target_field, point),
        )

    def act(self, state: AgentState, frame: Frame) -> Action:
        """The action for the frame seen in ``state``."""
        y = state.position[1]
        if self.ground.on_floor(y):
            level = self.ground.level(y)
            self.maps.of(level, state).update(frame.depth, self.maps.pose(state), 0.0)
            self.stairs.note(level, self.maps)
        if self.seen_at is None:
            seen = self._seen_goal(frame)
            if seen is not None:
                self.seen_at = self._frames
                if self.others:
                    self._aim_at(*seen)
        self._frames += 1
        if self.scan_left > 0:
            self.scan_left -= 1
            return self._scan_turn
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
        down = self.sim.render_instance_ids(AgentState(state.position, state.yaw, DOWN_TILT))
        if best_central_pixels((frame.instance_ids, down), self.target.id) >= cfg.final_pixels:
            return Action.STOP
        if self._relocations >= cfg.relocations:
            return Action.STOP
        stand = self._better_stand(state)
        if stand is None:
            return Action.STOP
        self._relocations += 1
        field_ = self.ground.field([stand])
        radius = self.follower.goal_radius
        self.follower = LatticeFollower(self.ground.nav, field_, radius, self.sim.config.motion)
        action = self.follower.next_action(state)
        if action is None:
            action = self._greedy(field_).next_action(state)
        return action

    def _better_stand(self, state: AgentState) -> Point3 | None:
        """The nearest untried view point, away from here, whose rendered views (from the
        point and from points around it, since the follower stops only near it), facing the
        target with a yaw reachable by whole turns, show enough of it in the middle."""
        x, y, z = state.position
        ground = self.ground
        here = ground.field([ground.snap(x, y, z)])
        options = [
            p
            for p in self.view_points
            if p not in self._tried_stands and math.hypot(p[0] - x, p[2] - z) > _STAND_SPREAD
        ]
        options.sort(key=lambda p: (ground.distance(here, p), p))
        for point in options[: self.config.stand_candidates]:
            self._tried_stands.add(point)
            if ground.distance(here, point) < math.inf and self._shows_target_around(point, state):
                return point
        return None

    def _shows_target_around(self, point: Point3, state: AgentState) -> bool:
        d = _STAND_SPREAD / 2.0
        for dx, dz in ((0.0, 0.0), (d, 0.0), (-d, 0.0), (0.0, d), (0.0, -d)):  # centre first
            position = (point[0] + dx, point[1], point[2] + dz)
            yaw = state.yaw
            yaw += self.turn * round(self._facing_error(position, yaw) / self.turn)
            views = tuple(
                self.sim.render_instance_ids(AgentState(position, yaw, t)) for t in (0.0, DOWN_TILT)
            )
            if best_central_pixels(views, self.target.id) < self.config.final_pixels:
                return False
        return True

    def _facing_error(self, position: tuple[float, float, float], yaw: float) -> float:
        cx, _, cz = self.target.box.center
        return wrap_angle(yaw_of(cx - position[0], cz - position[2]) - yaw)

    def _explore(self, state: AgentState) -> Action | None:
        """The next step toward the current frontier (or flight); a new one when it is
        reached, no longer a frontier, or taking too long; None when none is left."""
        for _ in range(self.config.goal_attempts):
            needs_goal = self._goal_follower is None or self._goal_done()
            if needs_goal and not self._choose_goal(state):
                return None
            follower = self._goal_follower
            if follower is None:
                return None
            action = follower.next_action(state)
            if action == Action.STOP:
                if self._goal_flight is not None:
                    action = self._arrive(state)
                else:
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
            grid = self.maps.of(self._goal_level, state)
            self._look_yaw = unexplored_heading(grid, self.maps.pose(state), point, self.turn)
            self._looked = True
        if self._look_yaw is not None:
            turn = turn_toward(wrap_angle(self._look_yaw - state.yaw), self.turn)
            if turn is not None:
                return turn
            self._look_yaw = None
        return None

    def _arrive(self, state: AgentState) -> Action | None:
        """At the far end of a flight: the first time on a storey, look round, turning first
        toward the side where the storey opens (a landing often faces a wall)."""
        self._drop_goal()
        level = self.ground.level(state.position[1])
        if not self.stairs.first_visit(level):
            return None
        heading = self.ground.open_heading(state.position)
        right = heading is not None and wrap_angle(heading - state.yaw) < 0.0
        self._scan_turn = Action.TURN_RIGHT if right else Action.TURN_LEFT
        self.scan_left = _ARRIVAL_SCAN_TURNS - 1
        return self._scan_turn

    # ----------------------------------------------------------------- frontiers
    def _goal_done(self) -> bool:
        """Time to choose again: no goal, too long on it, or its frontier has been cleared
        (no unexplored cell left within ``frontier_clear_radius`` of the frontier point).
        A flight is walked until its far end is reached."""
        if self._goal_flight is not None:
            return False
        if self._goal_frontier is None or self._goal_age >= self.config.goal_timeout:
            self._drop_goal()
            return True
        grid = self.maps.maps[self._goal_level]
        gx, gz = self._goal_frontier
        row, col = grid.cell_of(gx - self.origin[0], gz - self.origin[1])
        k = math.ceil(self.config.frontier_clear_radius / grid.cell_size)
        window = grid.explored[max(row - k, 0) : row + k + 1, max(col - k, 0) : col + k + 1]
        if window.all():
            self._drop_goal()
            return True
        return False

    def _drop_goal(self) -> None:
        """Forget the goal; a frontier is not chosen again, a flight at most twice."""
        self._look_yaw, self._looked = None, False
        if self._goal is not None and self._goal_frontier is not None:
            self.maps.visit(self._goal_level, (self._goal[0], self._goal[2]), self._goal_frontier)
        self._goal = self._goal_follower = self._goal_flight = None

    def _choose_goal(self, state: AgentState) -> bool:
        x, y, z = state.position
        ground = self.ground
        level = ground.level(y)
        if not ground.on_floor(y):  # started on the stairs: off them, toward the target
            return self._leave_stairs(level)
        floor = ground.floor_y(level)
        self.maps.of(level, state)
        cfg = self.config
        points = self.maps.frontier_points(
            level, cfg.min_frontier_cells, cfg.min_pocket_area, cfg.visited_radius
        )
        if points.shape[0] == 0 and not self.stairs.flights:
            return False
        here = ground.field([ground.snap(x, y, z)])
        world = points + np.array(self.origin)
        snapped = [ground.snap(float(px), floor, float(pz)) for px, pz in world]
        reach = np.array([ground.distance(here, p) for p in snapped])
        # A frontier whose walkable point is already underfoot cannot be cleared by walking;
        # one whose point is on the stairs (seen down a stairwell) is not on this storey.
        underfoot = reach < cfg.frontier_reached
        underfoot |= np.array([p[1] != floor for p in snapped], bool).reshape(-1)
        for raw, goal, under in zip(world, snapped, underfoot, strict=True):
            if under:
                self.maps.visit(level, (float(raw[0]), float(raw[1])), (goal[0], goal[2]))
        reach[underfoot] = np.inf
        toward = self.stairs.toward_target(level)
        if toward is not None:
            self.chooser.log_best(toward.end_on(level))
            return self._walk_to(self._take_flight(toward, level), level, flight=True)
        flights = self.stairs.options(level, exhausted=not np.isfinite(reach).any())
        if flights:
            ends = [f.end_on(level) for f in flights]
            offsets = [(p[0] - self.origin[0], p[2] - self.origin[1]) for p in ends]
            points = np.concatenate([points, np.array(offsets, np.float64)])
            reach = np.concatenate([reach, [ground.distance(here, p) for p in ends]])
        if points.shape[0] == 0:
            return False
        self.chooser.height = floor if ground.storeys is not None else None
        index = self.chooser(points, reach, self._previous, self.rng, cfg.chooser)
        if index is None:
            return False
        self._previous = (float(points[index, 0]), float(points[index, 1]))
        if index >= len(snapped):
            flight = flights[index - len(snapped)]
            return self._walk_to(self._take_flight(flight, level), level, flight=True)
        self._goal = snapped[index]
        self._goal_frontier = (float(world[index, 0]), float(world[index, 1]))
        return self._walk_to(self._goal, level, flight=False)

    def _walk_to(self, goal: Point3, level: int, flight: bool) -> bool:
        """Follow collision-free walks to the chosen goal (a flight's: a longer search)."""
        field_ = self.ground.field([goal])
        motion, radius = self.sim.config.motion, self.config.frontier_reached
        expansions = 30000 if flight else 6000
        self._goal_follower = LatticeFollower(self.ground.nav, field_, radius, motion, expansions)
        self._goal_level = level
        self._goal_age = 0
        return True

    # ----------------------------------------------------------------- stairs
    def _leave_stairs(self, level: int) -> bool:
        """Walk to the end of the flight underfoot that is nearer the target."""
        nearer = self.stairs.nearer_end(level)
        if nearer is None:
            return False
        flight, end = nearer
        self._goal_flight = flight
        self._goal = end
        self._goal_frontier = None
        self._previous = (end[0] - self.origin[0], end[2] - self.origin[1])
        return self._walk_to(end, level, flight=True)

    def _take_flight(self, flight: Flight, level: int) -> Point3:
        """Make the flight's far end the goal; the next choice starts from there."""
        self.stairs.took(flight, level)
        self._goal_flight = flight
        arrival = self._goal = flight.arrival(level)
        self._goal_frontier = None
        self._previous = (arrival[0] - self.origin[0], arrival[2] - self.origin[1])
        return arrival

    # ----------------------------------------------------------------- helpers
    def _seen_goal(self, frame: Frame) -> tuple[ObjectInstance, tuple[Point3, ...]] | None:
        """The goal the frame shows enough of within range (of several, the most visible)."""
        best, most = None, 0
        for goal in self.others or ((self.target, self.view_points),):
            mine = frame.instance_ids == goal[0].id
            count = int(np.count_nonzero(mine))
            if count < self.config.seen_pixels or count <= most:
                continue
            depth = frame.depth[mine]
            if depth[depth > 0.0].min(initial=math.inf) <= self.config.seen_range:
                best, most = goal, count
        return best

    def _aim_at(self, target: ObjectInstance, view_points: tuple[Point3, ...]) -> None:
        """Make the seen goal the target: walk to its own nearest view point."""
        self.target, self.view_points = target, view_points
        field_ = self.ground.field(view_points)
        radius, motion = self.follower.goal_radius, self.sim.config.motion
        self.follower = LatticeFollower(self.ground.nav, field_, radius, motion, 30000)

    def _greedy(self, field_: GeodesicField | StoreyField) -> GreedyFollower:
        radius = self.follower.goal_radius
        return GreedyFollower(self.ground.nav, field_, radius, self.sim.config.motion)
