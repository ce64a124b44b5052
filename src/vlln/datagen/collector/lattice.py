"""Collision-free walks on the agent's motion lattice, for trajectories worth training on.

The greedy follower picks one step at a time and, in a doorway met at an angle, may have no
gaining move that does not scrape the wall; the collected trajectory would then be dropped for
its collision. Searching the lattice of states reachable by the agent's own actions (FORWARD
0.25 m, turns of 30°) with A*, using only moves that do not collide and the geodesic distance
as the heuristic, finds a walk that avoids the scrape whenever one exists.

In a house with several storeys the lattice spans them: states carry their height, which
follows the stairs, so a search can climb or descend a flight.
"""

from __future__ import annotations

import heapq
import itertools
import math

from vlln.sim.agent import Action, AgentState, MotionConfig, step
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.storey_field import StoreyField
from vlln.sim.storeys import Storeys
from vlln.world.frame import wrap_angle

_KEY_CELL = 0.05  # m; states closer than this (same heading) count as one
_WEIGHT = 1.5  # weighted A*: a little longer than optimal, far fewer expansions
_RETRY_AFTER = 8  # steps taken by other means before a failed search is tried again

_Key = tuple[int, int, int, int]  # a state's cell in x, y and z, and its heading


def plan_walk(
    grid: NavGrid | Storeys,
    field: GeodesicField | StoreyField,
    motion: MotionConfig,
    start: AgentState,
    goal_radius: float,
    max_expansions: int = 6000,
) -> list[Action] | None:
    """Actions from ``start`` to a state nearer than ``goal_radius`` to the field's goals,
    never colliding; None when the search finds none within ``max_expansions``."""
    forward = motion.forward_step
    turn = motion.turn
    turns = max(1, round(360.0 / motion.turn_deg))

    def estimate(state: AgentState) -> float:
        x, y, z = state.position
        return field.distance(x, z, y) / forward

    def key(state: AgentState, heading: int) -> _Key:
        x, y, z = state.position
        return round(x / _KEY_CELL), round(y / _KEY_CELL), round(z / _KEY_CELL), heading

    if estimate(start) == math.inf:
        return None
    order = itertools.count()
    frontier = [(_WEIGHT * estimate(start), next(order), 0, start, 0)]
    parents: dict[_Key, tuple[_Key | None, Action | None]] = {key(start, 0): (None, None)}
    costs = {key(start, 0): 0}
    expansions = 0
    while frontier and expansions < max_expansions:
        _, _, cost, state, heading = heapq.heappop(frontier)
        here = key(state, heading)
        if cost > costs[here]:
            continue
        if estimate(state) * forward < goal_radius:
            return _actions(parents, here)
        expansions += 1
        moved = step(state, Action.MOVE_FORWARD, grid, motion)
        successors = [
            (Action.TURN_LEFT, _turned(state, turn), (heading + 1) % turns),
            (Action.TURN_RIGHT, _turned(state, -turn), (heading - 1) % turns),
        ]
        if not moved.collided:
            successors.insert(0, (Action.MOVE_FORWARD, moved.state, heading))
        for action, next_state, next_heading in successors:
            there = key(next_state, next_heading)
            if there == here or cost + 1 >= costs.get(there, math.inf):
                continue
            costs[there] = cost + 1
            parents[there] = (here, action)
            priority = cost + 1 + _WEIGHT * estimate(next_state)
            heapq.heappush(frontier, (priority, next(order), cost + 1, next_state, next_heading))
    return None


def _turned(state: AgentState, angle: float) -> AgentState:
    """A turn in place (turns never collide; same result as :func:`step`)."""
    return AgentState(state.position, wrap_angle(state.yaw + angle), state.tilt)


def _actions(parents: dict[_Key, tuple[_Key | None, Action | None]], end: _Key) -> list[Action]:
    actions: list[Action] = []
    node: _Key | None = end
    while node is not None:
        previous, action = parents[node]
        if action is not None:
            actions.append(action)
        node = previous
    actions.reverse()
    return actions


class LatticeFollower:
    """Follows :func:`plan_walk` plans to a field's goals; STOP once nearer than the radius.

    Each planned action is checked against the current state before it is taken, and the walk
    is planned again when it would collide (states merged by the search differ by a few
    centimetres) or when it has run out. :meth:`next_action` is None when no collision-free
    walk is found (and for the next few steps, which the caller takes by other means, so that
    a hopeless search is not repeated every step); the caller decides what then.
    """

    def __init__(
        self,
        grid: NavGrid | Storeys,
        field: GeodesicField | StoreyField,
        goal_radius: float,
        motion: MotionConfig,
        max_expansions: int = 6000,
    ) -> None:
        self.grid = grid
        self.field = field
        self.goal_radius = goal_radius
        self.motion = motion
        self.max_expansions = max_expansions
        self._plan: list[Action] = []
        self._cooldown = 0  # steps left before searching again after a failed search

    def next_action(self, state: AgentState) -> Action | None:
        x, y, z = state.position
        if self.field.distance(x, z, y) < self.goal_radius:
            return Action.STOP
        if not self._plan or step(state, self._plan[0], self.grid, self.motion).collided:
            if self._cooldown > 0:
                self._cooldown -= 1
                return None
            plan = plan_walk(
                self.grid, self.field, self.motion, state, self.goal_radius, self.max_expansions
            )
            self._plan = plan or []
            if not plan:
                self._cooldown = _RETRY_AFTER
                return None
        return self._plan.pop(0)
