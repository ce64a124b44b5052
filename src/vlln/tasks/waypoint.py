"""The walk to a pixel goal: where it is, and the next step of a follower toward it.

A :class:`~vlln.tasks.spec.PixelGoal` becomes a navigable floor point
(:func:`vlln.sim.pixel_goal.pixel_floor_goal`); the environment then offers the shortest-path
follower's next action toward it in every observation until the agent is within the follower's
radius (0.25 m, as in the reference), takes another action, or sets another goal. The agent
decides how many of these steps to take (the model agent: at most 8 before asking again).
A pixel whose point is already within the radius, or that no forward step brings closer, gives
no waypoint: the goal would not move the agent, and a model that names it again on the same
frame would loop.
In a house with several storeys the point is ``(x, y, z)`` on the agent's storey and the
follower walks the storeys' graph, up or down a flight when the point is on it.

The follower's field is first built only :data:`WAYPOINT_REACH` deep around the point, and
over the whole house only when the agent stands farther (:func:`waypoint_field`). The walk is
the same either way: the follower only compares places nearer to the point than the agent
(a move must gain distance), the agent only comes nearer while it follows, and a bounded
field is exact at every place within its bound.
"""

from __future__ import annotations

from dataclasses import dataclass

from vlln.errors import NavigationError
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import ForwardProbes, GreedyFollower
from vlln.sim.pixel_goal import pixel_floor_goal
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Field, Simulator
from vlln.sim.viewpoints import GoalPoint

WAYPOINT_RADIUS = 0.25
# Metres of the first, bounded field: the data's pixel goals are at most 8 forward steps
# (2 m) ahead, and a field's cost grows with the area it covers.
WAYPOINT_REACH = 3.0


@dataclass(frozen=True)
class Waypoint:
    """A floor point to walk to and the follower that leads there."""

    point: GoalPoint
    follower: GreedyFollower

    def next_action(self, state: AgentState) -> Action | None:
        """The follower's next move, or None once the point is reached or cannot be."""
        try:
            action = self.follower.next_action(state)
        except NavigationError:
            return None
        return None if action == Action.STOP else action


def waypoint_for_pixel(
    sim: Simulator,
    frame: Frame,
    col: int,
    row: int,
    state: AgentState,
    probes: ForwardProbes | None = None,
) -> Waypoint | str:
    """The waypoint that pixel ``(col, row)`` of ``frame``, taken at ``state``, points to, or
    a short reason why it gives none. ``probes`` lets followers to several pixels share their
    moves (:class:`ForwardProbes`)."""
    spec = sim.config.camera
    if not (0 <= col < spec.width and 0 <= row < spec.height):
        return f"pixel ({col}, {row}) is outside the {spec.width}x{spec.height} image"
    point = pixel_floor_goal(spec, sim.nav, frame.depth, col, row, state)
    if point is None:
        return f"pixel ({col}, {row}) shows nothing"
    field = waypoint_field(sim, point, state)
    x, y, z = state.position
    if not field.is_reachable(x, z, y):
        return f"pixel ({col}, {row}) shows floor that cannot be reached"
    follower = GreedyFollower(sim.nav, field, WAYPOINT_RADIUS, sim.config.motion, probes)
    waypoint = Waypoint(point, follower)
    if waypoint.next_action(state) is None:
        return f"pixel ({col}, {row}) shows floor the agent stands on or cannot step toward"
    return waypoint


def waypoint_field(sim: Simulator, point: GoalPoint, state: AgentState) -> Field:
    """The distance field to ``point``, exact wherever it is nearer than the agent at
    ``state``: :data:`WAYPOINT_REACH` deep when the agent is within that, else the whole
    house's (module doc)."""
    x, y, z = state.position
    near = sim.distance_field([point], limit=WAYPOINT_REACH)
    if near.distance(x, z, y) <= WAYPOINT_REACH:
        return near
    return sim.distance_field([point])
