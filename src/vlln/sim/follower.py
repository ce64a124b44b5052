"""A greedy shortest-path follower: the expert that answers "what should I do next?".

It drives data collection (shortest-path segments of trajectories), the oracle's step-level
route answers ("turn left", "go forward") and the model's pixel-goal execution.

Rather than steering toward a polyline, which breaks at corners when headings come in 30°
steps, it simulates one FORWARD from each reachable heading with the real motion model and
scores the result on the geodesic field. The heading to aim for depends only on the position,
so the follower never turns back and forth; every FORWARD it takes shortens the geodesic
distance, so it never revisits a position.
"""

from __future__ import annotations

import math

from vlln.errors import ConfigError, NavigationError
from vlln.sim.agent import Action, AgentState, MotionConfig, step
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.storey_field import StoreyField
from vlln.sim.storeys import Point3, Storeys

# Headings gaining within this share of a step of the best are as good; the one needing the
# fewest turns wins.
_EQUAL_GAIN = 0.02

Probe = tuple[int, Point3, bool]  # turns (positive = left), where FORWARD then ends, collided


class ForwardProbes:
    """The FORWARD move from every heading reachable by whole turns, per place, remembered.

    Where such a move ends depends on the place, the heading and the grid, never on the goal,
    so followers to different goals asked about the same places can share one: the data build
    walks each teacher state with the followers of the pixel goals of up to eight earlier
    frames, and the moves (a cell walk each, twelve per state) were most of that check's cost.
    Give one to :class:`GreedyFollower`; keep it only while the places it is asked about are
    few (it is unbounded). With ``remember`` off it only makes the moves (a follower's own,
    by default: one follower rarely sees a place twice).
    """

    def __init__(
        self, grid: NavGrid | Storeys, motion: MotionConfig | None = None, remember: bool = True
    ) -> None:
        self.grid = grid
        self.motion = motion if motion is not None else MotionConfig()
        self.remember = remember
        # Headings as whole turns from the current one, fewest turns first, left before right.
        headings = max(1, round(360.0 / self.motion.turn_deg))
        left = headings // 2
        right = headings - 1 - left
        self.offsets = [0]
        for k in range(1, left + 1):
            self.offsets += [k, -k] if k <= right else [k]
        self._known: dict[tuple[Point3, float], list[Probe]] = {}

    def around(self, state: AgentState) -> list[Probe]:
        """The move from each heading of ``state``, in :attr:`offsets` order."""
        key = (state.position, state.yaw)
        known = self._known.get(key)
        if known is None:
            known = []
            turn = self.motion.turn
            for k in self.offsets:
                probe = AgentState(state.position, state.yaw + k * turn, state.tilt)
                result = step(probe, Action.MOVE_FORWARD, self.grid, self.motion)
                known.append((k, result.state.position, result.collided))
            if self.remember:
                self._known[key] = known
        return known


class GreedyFollower:
    """Chooses the next action toward the goals of a :class:`GeodesicField`.

    STOP when the geodesic distance is below ``goal_radius``. Otherwise, among the headings
    reachable by whole turns, aim for the one whose FORWARD gains the most geodesic distance
    (collision-free moves first); FORWARD if already facing it, else turn toward it.
    """

    def __init__(
        self,
        grid: NavGrid | Storeys,
        field: GeodesicField | StoreyField,
        goal_radius: float = 0.25,
        motion: MotionConfig | None = None,
        probes: ForwardProbes | None = None,
    ) -> None:
        if not goal_radius > 0.0:
            raise ConfigError(f"goal_radius must be positive metres, got {goal_radius}")
        if field.grid is not grid:
            raise ConfigError("the geodesic field was built on a different grid")
        self.grid = grid
        self.field = field
        self.goal_radius = float(goal_radius)
        self.motion = motion if motion is not None else MotionConfig()
        self.probes = probes or ForwardProbes(grid, self.motion, remember=False)
        if self.probes.grid is not grid or self.probes.motion != self.motion:
            raise ConfigError("the forward probes were made for another grid or motion")

    def next_action(self, state: AgentState) -> Action:
        x, y, z = state.position
        distance = self.field.distance(x, z, y)
        if distance < self.goal_radius:
            return Action.STOP
        if distance == math.inf:
            raise NavigationError(
                f"no goal can be reached from ({x:.3f}, {z:.3f}); the follower has no action"
            )
        turns = self._best_heading(state, distance)
        if turns == 0:
            return Action.MOVE_FORWARD
        return Action.TURN_LEFT if turns > 0 else Action.TURN_RIGHT

    def _best_heading(self, state: AgentState, distance: float) -> int:
        """Turns (positive = left) toward the heading whose FORWARD gains the most distance.

        Collision-free moves are preferred (data collection drops trajectories with any
        collision); a colliding move is chosen only when no free one gets closer.
        """
        forward = self.motion.forward_step
        free: list[tuple[float, int]] = []
        colliding: list[tuple[float, int]] = []
        for k, (x, y, z), collided in self.probes.around(state):
            gain = distance - self.field.distance(x, z, y)
            if gain > 0.0:
                (colliding if collided else free).append((gain, k))
        candidates = free or colliding
        if not candidates:
            x, _, z = state.position
            raise NavigationError(
                f"no forward move from ({x:.3f}, {z:.3f}) gets closer to the goals; the "
                "navigable area narrows there below what the agent can pass"
            )
        good_enough = max(gain for gain, _ in candidates) - _EQUAL_GAIN * forward
        # Candidates are in order of fewest turns.
        return next(k for gain, k in candidates if gain >= good_enough)
