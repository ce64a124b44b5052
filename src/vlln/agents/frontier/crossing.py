"""When to take the stairs, and the walk over them.

A flight is the way to unexplored space on another storey: the agent takes it once its own
storey has no frontier left (toward a storey it has not seen first, then toward one whose
frontiers did not run out), or at once when the oracle said the target is upstairs or
downstairs and the map shows a flight that way. What the oracle said also rules out every
storey on the wrong side of the one it was said on; directions that name no storey mean the
target is on the storey they were given on, which the agent then does not leave (or goes back
to).

A walk follows the path of :func:`stairs.stairs_path`, going on straight along the flight
while the feet are off any floor, and ends when they stand on another storey's floor. It
fails (and that flight is not tried again) when the agent gets stuck or the path ends on the
floor it left. A flight down that shows only its head is first looked at: the agent walks to
the head, faces down the flight (across the top tread) and looks down.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from vlln.agents.frontier.explorer import look_heading
from vlln.agents.frontier.mapping import Pose
from vlln.agents.frontier.planner import PathFollower, turn_toward
from vlln.agents.frontier.stairs import (
    StairExit,
    head_facing,
    stair_exits,
    stair_heads,
    stairs_path,
    straight_on,
)
from vlln.agents.frontier.storeys import StoreyMemory
from vlln.sim.agent import Action
from vlln.world.frame import wrap_angle

_HINT_MARGIN = 0.5  # m: a storey counts as above (below) a floor this much higher (lower)
_MAX_WALK = 80  # steps a walk over stairs may take
_MAX_BUMPS = 5  # bumps on the way to the head of a flight before it is given up
_ON_FLIGHT = 0.05  # m from a floor: a cell walked at this height is on the flight


@dataclass
class _Walk:
    departure: int
    direction: int
    known: int  # storeys known when it began: an arrival beyond them is a new storey
    axis: tuple[float, float]  # the flight's, away from the departure storey
    follower: PathFollower
    trail: list[tuple[float, float, float]] = field(default_factory=list)


@dataclass
class _Peek:
    follower: PathFollower  # to the head of the flight
    head: tuple[float, float]
    facing: float | None = None
    looked: bool = False
    bumps: int = 0  # forward moves that made no way: each one asks for a new path


class Crossing:
    """Takes the stairs between the storeys of a :class:`StoreyMemory`."""

    def __init__(self, memory: StoreyMemory, turn: float) -> None:
        self.memory = memory
        self.turn = turn
        # (floor it was said on, +1 up / -1 down / 0 there)
        self.hint: tuple[float, int] | None = None
        self.arrived_new = False  # the last walk ended on a storey not seen before
        self.walk_ended = False  # a walk ended (the agent resets its plans); cleared by it
        self._walk: _Walk | None = None
        self._peek: _Peek | None = None
        self._failed: set[tuple[int, int]] = set()
        self._peeked: set[int] = set()

    def bumped(self, pose: Pose) -> None:
        """A forward move made no way (the map now shows what was in the way): the way to the
        head of a flight is planned again, at most ``_MAX_BUMPS`` times."""
        peek = self._peek
        if peek is None or peek.looked:
            return
        peek.bumps += 1
        here = self.memory.here
        distances = here.explorer.stairs_distances(pose)
        row, col = here.map.cell_of(*peek.head)
        if peek.bumps > _MAX_BUMPS or not np.isfinite(distances.distance(row, col)):
            self._peek = None
            self._peeked.add(self.memory.current)
            return
        peek.follower = PathFollower(distances.path_to(row, col), self.turn, tolerance=0.3)

    @property
    def busy(self) -> bool:
        return self._walk is not None or self._peek is not None

    # ----------------------------------------------------------------- the oracle's word
    def note_hint(self, direction: int) -> None:
        """The oracle said the target is upstairs (+1), downstairs (-1) or on this storey (0)."""
        self.hint = (self.memory.here.floor, direction)

    def fits_hint(self, storey: int) -> bool:
        """Whether the target may be on that storey, by what the oracle said."""
        if self.hint is None:
            return True
        said_on, direction = self.hint
        rise = self.memory.storeys[storey].floor - said_on
        if direction == 0:
            return abs(rise) < _HINT_MARGIN
        return direction * rise > _HINT_MARGIN

    def _wanted(self) -> int | None:
        """The way (+1 up, -1 down) to the storeys the oracle's word points to; None when
        the agent is on one of them or nothing was said."""
        if self.hint is None or self.fits_hint(self.memory.current):
            return None
        said_on, direction = self.hint
        if direction == 0:
            return 1 if said_on > self.memory.here.floor else -1
        return direction

    # ----------------------------------------------------------------- starting a walk
    def toward_hint(self, pose: Pose, height: float) -> Action | None:
        """The first move of a walk the oracle's word calls for, when the map shows a flight."""
        wanted = self._wanted()
        return None if wanted is None else self._start(pose, height, [wanted])

    def leave(self, pose: Pose, height: float) -> Action | None:
        """The first move of a walk to a storey worth exploring, once this one is done."""
        memory = self.memory
        fresh, unfinished = [], []
        for direction in (1, -1):
            end = memory.links.get((memory.current, direction))
            if not self._allowed(direction, end):
                continue
            if end is None:
                fresh.append(direction)
            elif not memory.storeys[end].exhausted:
                unfinished.append(direction)
        return self._start(pose, height, fresh + unfinished)

    def _allowed(self, direction: int, end: int | None) -> bool:
        """Whether the oracle's word leaves a flight worth taking: toward the hinted side while
        short of it, and never back across it."""
        if self.hint is None:
            return True
        if not self.fits_hint(self.memory.current):
            return direction == self._wanted()
        return self.hint[1] != 0 and (end is None or self.fits_hint(end))

    def _start(self, pose: Pose, height: float, directions: list[int]) -> Action | None:
        memory = self.memory
        here = memory.here
        flights = {f.direction: f for f in stair_exits(here.map)}
        for direction in directions:
            if (memory.current, direction) in self._failed:
                continue
            flight = flights.get(direction)
            if flight is None:
                if direction < 0 and memory.current not in self._peeked:
                    action = self._start_peek(pose, height)
                    if action is not None:
                        return action
                continue
            path = self._path(pose, flight)
            if path is None:
                self._failed.add((memory.current, direction))
                continue
            follower = PathFollower(path, self.turn)
            self.arrived_new = False
            walk = _Walk(memory.current, direction, len(memory.storeys), flight.axis, follower)
            self._walk = walk
            return self.step(pose, height, stuck=False)
        return None

    def _start_peek(self, pose: Pose, height: float) -> Action | None:
        """Go and look down the nearest head of a flight down, if the map shows one."""
        here = self.memory.here
        heads = stair_heads(here.map)
        if heads.size == 0:
            return None
        distances = here.explorer.stairs_distances(pose)
        n_cols = here.map.shape[1]
        reach = [distances.distance(int(c // n_cols), int(c % n_cols)) for c in heads]
        best = int(np.argmin(reach))
        if not np.isfinite(reach[best]):
            self._peeked.add(self.memory.current)
            return None
        row, col = int(heads[best] // n_cols), int(heads[best] % n_cols)
        follower = PathFollower(distances.path_to(row, col), self.turn, tolerance=0.3)
        self._peek = _Peek(follower, here.map.cell_centre(row, col))
        return self.step(pose, height, stuck=False)

    def _peek_step(self, pose: Pose, height: float, stuck: bool) -> Action | None:
        peek = self._peek
        assert peek is not None
        current = self.memory.current
        if stuck:
            self._peek = None
            self._peeked.add(current)
            return None
        if not peek.looked:
            action = peek.follower.next_action(pose)
            if action is not None:
                return action
            if peek.facing is None:
                peek.facing = head_facing(self.memory.here.map, pose, peek.head)
                if peek.facing is None:
                    peek.facing = look_heading(self.memory.here.map, pose, self.turn)
                if peek.facing is None:
                    peek.facing = pose.yaw
            turn = turn_toward(wrap_angle(peek.facing - pose.yaw), self.turn)
            if turn is not None:
                return turn
            peek.looked = True
            return Action.LOOK_DOWN
        self._peek = None
        self._peeked.add(current)
        action = self._start(pose, height, [-1])
        if action is None:
            self._failed.add((current, -1))
        return action

    def _path(self, pose: Pose, flight: StairExit) -> list[tuple[float, float]] | None:
        here = self.memory.here
        return stairs_path(here.map, here.explorer.stairs_distances(pose), flight)

    # ----------------------------------------------------------------- walking
    def step(self, pose: Pose, height: float, stuck: bool) -> Action | None:
        """The next move of the walk (or of the look down a flight); None once it has ended
        (see :attr:`walk_ended`, :attr:`arrived_new`)."""
        if self._peek is not None:
            return self._peek_step(pose, height, stuck)
        walk = self._walk
        if walk is None:
            return None
        memory = self.memory
        walk.trail.append((pose.x, pose.z, height))
        if memory.current != walk.departure and memory.on_floor(height):
            self._arrive(walk)
            return None
        action = walk.follower.next_action(pose)
        if action is None and not memory.on_floor(height):
            # Still on the steps (the map saw only part of the flight): keep going.
            ahead = straight_on((pose.x, pose.z), walk.axis, memory.here.map.cell_size)
            walk.follower = PathFollower(ahead, self.turn)
            action = walk.follower.next_action(pose)
        if action is None or stuck or len(walk.trail) > _MAX_WALK:
            self._failed.add((walk.departure, walk.direction))
            self._walk = None
            self.walk_ended = True
            return None
        return action

    def _arrive(self, walk: _Walk) -> None:
        """Remember where the flight leads, and put the cells walked on the stairs into the
        maps of both storeys (the scan may not see all of them)."""
        memory = self.memory
        memory.link(walk.departure, walk.direction, memory.current)
        trail = np.asarray(walk.trail, np.float64)
        ends = (memory.storeys[walk.departure], memory.here)
        on_flight = np.ones(len(trail), bool)
        for storey in ends:
            on_flight &= np.abs(trail[:, 2] - storey.floor) > _ON_FLIGHT
        for storey in ends:
            rise = trail[on_flight, 2] - storey.floor
            storey.map.mark_stairs(trail[on_flight, 0], trail[on_flight, 1], rise)
            storey.explorer.drop_path()
        self.arrived_new = memory.current >= walk.known
        self._walk = None
        self.walk_ended = True
