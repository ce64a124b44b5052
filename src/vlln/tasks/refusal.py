"""Episodes that cannot be played honestly in their scene, and why.

A start or a goal view point belongs to the storey whose floor is nearest its height. An
episode whose start is on no storey of the scene, or is not navigable on its storey, or from
which no path leads to a goal on the goal's storey (a scan whose stairs could not be joined,
an episode file made for another scene), is refused: played anyway, it would put the agent or
its target on a storey where it is not, and a target upstairs would be a step away on the
ground floor's plan (a false success). The environment raises
:class:`~vlln.errors.EpisodeRefusedError` with the reason; a runner records it and goes on.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from vlln.sim.simulator import Field, Simulator
from vlln.sim.viewpoints import GoalPoint

# m: a start or view point this far from its storey's walking height is on no storey.
HEIGHT_TOLERANCE = 0.5


def _floors(sim: Simulator) -> str:
    floors = sim.storeys.floor_ys if sim.storeys is not None else (sim.grid.floor_y,)
    return ", ".join(f"{y:.2f}" for y in floors)


def start_problem(sim: Simulator, x: float, y: float, z: float) -> str | None:
    """Why the start ``(x, y, z)`` is on no storey or not navigable on its own, or ``None``."""
    if sim.storeys is not None:
        level = sim.storeys.level_of(y)
        plane, walking = sim.storeys.grids[level], sim.storeys.height_at(level, x, z)
    else:
        level, plane, walking = 0, sim.grid, sim.grid.floor_y
    if abs(y - walking) > HEIGHT_TOLERANCE:
        floors = _floors(sim)
        return f"its start height {y:.2f} m is on no storey of the scene (floors at {floors} m)"
    if not plane.is_navigable(x, z):
        sx, sz = plane.snap_point(x, z)
        return (
            f"its start ({x:.2f}, {y:.2f}, {z:.2f}) is not navigable on storey {level} "
            f"(the nearest navigable point is ({sx:.2f}, {sz:.2f}))"
        )
    return None


def on_the_storey(sim: Simulator, y: float) -> bool:
    """Whether a view point at height ``y`` can be on a one-storey scene's floor."""
    return sim.storeys is not None or abs(y - sim.grid.floor_y) <= HEIGHT_TOLERANCE


def no_goal_reason(sim: Simulator, listed: int) -> str:
    """Why an episode has no goal point: its ``listed`` view points are all off the scene's
    storey, or its goals have none that is navigable."""
    if listed:
        return (
            f"its {listed} goal view points are on no storey of the scene (floors at "
            f"{_floors(sim)} m)"
        )
    return "none of its goals has a navigable view point on its storey"


def reach_problem(
    sim: Simulator, field: Field, start: Sequence[float], goals: Sequence[GoalPoint]
) -> str | None:
    """Why no path leads from ``start`` to the goals on their storeys, or ``None``."""
    x, y, z = start
    if field.distance(x, z, y) < math.inf:
        return None
    if sim.storeys is None:
        return "no path on the floor leads from its start to its goals"
    mine = sim.storeys.level_of(y)
    theirs = sorted({sim.storeys.level_of(goal[1]) for goal in goals if len(goal) == 3})
    if theirs and mine not in theirs:
        names = ", ".join(str(level) for level in theirs)
        return (
            f"no stairs join its start on storey {mine} to its goals on storey {names} "
            "(the scene's flights that could join them were left out or are missing)"
        )
    return f"no path on storey {mine} leads from its start to its goals"
