"""An IIGN episode toward one instance, for tests that play the oracle through the
environment."""

from __future__ import annotations

import numpy as np

from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.world.frame import yaw_to_quaternion
from vlln.world.model import ObjectInstance


def iign_episode(sim: Simulator, target: ObjectInstance, episode_id: str) -> Episode:
    """``target`` as the goal of "Search for the <category>.", from a navigable start drawn
    with a fixed seed."""
    goals = view_points(sim.grid, target.box)
    x, z = sim.grid.sample_navigable_point(np.random.default_rng(5), sim.grid.largest_component())
    box = target.box
    qx, qy, qz, qw = yaw_to_quaternion(0.3)
    return Episode(
        episode_id=episode_id,
        scene_id=f"vlln/{sim.house.name}",
        start_position=(x, 0.0, z),
        start_rotation=(qx, qy, qz, qw),
        object_category=target.category,
        goals=(
            Goal(
                box.center,
                None,
                (*box.min, *box.max),
                tuple(ViewPoint((gx, 0.0, gz)) for gx, gz in goals),
            ),
        ),
        instruction=Instruction("IIGN", f"Search for the {target.category}.", (str(target.id),)),
    )
