"""What a stop was at: the facts the failure taxonomy reads, taken from privileged geometry.

When an episode ends with STOP the environment records two facts about the stop, so that
:mod:`vlln.tasks.taxonomy` can tell a stop at a same-category distractor from a stop at an
object of another category or at nothing:

* the **stop instance**, the object the agent stopped at: among the objects it sees in a level
  view (at least :data:`STOP_OBJECT_MIN_PIXELS` pixels) within :data:`STOP_OBJECT_RANGE`
  metres of floor distance, a goal if there is one, else an instance of the target category,
  else the nearest; ties go to the object with more pixels;
* the **distractor distance**: the geodesic distance from the stop to the nearest view point
  of a same-category instance that is not a goal, measured exactly as the distance to the
  target is (:func:`distractor_distance`), so "near a distractor" means what "near the
  target" means and a distractor behind a wall is not near.
"""

from __future__ import annotations

import math
from collections.abc import Collection

import numpy as np
from numpy.typing import NDArray

from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.world.catalogue.aliases import canonical_category

STOP_OBJECT_MIN_PIXELS = 50
"""Pixels an object must cover in the level view to be what the agent stopped at."""

STOP_OBJECT_RANGE = 1.5
"""Metres of floor distance from the agent to the object's footprint, at most."""


def stop_instance(
    sim: Simulator, ids: NDArray[np.int32] | None, goals: Collection[int], category: str
) -> tuple[int | None, str | None]:
    """The instance the agent at ``sim.state`` stopped at, and its category (module doc).

    ``ids`` is the instance-id image of the current frame when the camera is level (None
    renders the level view).
    """
    state = sim.state
    if ids is None or state.tilt != 0.0:
        ids = sim.render_instance_ids(AgentState(state.position, state.yaw, 0.0))
    visible, pixels = np.unique(ids[ids > 0], return_counts=True)
    house = sim.house
    wanted = canonical_category(category)
    x, _, z = state.position
    best: tuple[int, float, int, int] | None = None
    for instance_id, count in zip(visible.tolist(), pixels.tolist(), strict=True):
        if count < STOP_OBJECT_MIN_PIXELS:
            continue
        inst = house.instance(instance_id)
        distance = inst.box.plan_distance(x, z)
        if distance > STOP_OBJECT_RANGE:
            continue
        same = canonical_category(inst.category) == wanted
        rank = 0 if instance_id in goals else 1 if same else 2
        key = (rank, round(distance, 1), -count, instance_id)
        if best is None or key < best:
            best = key
    if best is None:
        return None, None
    instance_id = best[3]
    return instance_id, house.instance(instance_id).category


def distractor_distance(sim: Simulator, goals: Collection[int], category: str) -> float | None:
    """Geodesic metres from the agent to the nearest view point of a same-category instance
    that is not a goal; None when there is none or none can be reached from the agent."""
    points = [
        point
        for inst in sim.house.instances_of(category)
        if inst.id not in goals
        for point in sim.view_points(inst.box)
    ]
    if not points:
        return None
    x, y, z = sim.state.position
    distance = sim.distance_field(points).distance(x, z, y)
    return distance if math.isfinite(distance) else None
