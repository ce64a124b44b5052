"""Episodes in a two-storey house: targets on the other storey, reached through the stairs."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.simulator import Simulator
from vlln.tasks.generation import generate_house_episodes
from vlln.tasks.scenes import (
    canonical_seed,
    procedural_floors,
    procedural_scene_id,
    procedural_seed,
)
from vlln.world.frame import quaternion_to_yaw
from vlln.world.generator import HouseParameters, generate_house

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    with Simulator(generate_house(1, SMALL_TWO_STOREYS)) as simulator:
        yield simulator


def test_scene_ids_name_the_storeys() -> None:
    scene = procedural_scene_id(12, 2)
    assert scene == "vlln/house_00012_2f/house_00012_2f.glb"
    assert (procedural_seed(scene), procedural_floors(scene), canonical_seed(scene)) == (12, 2, 12)
    assert procedural_scene_id(12) == "vlln/house_00012/house_00012.glb"
    assert procedural_floors(procedural_scene_id(12)) == 1


def test_ign_episodes_with_targets_on_the_other_storey_are_solved(sim: Simulator) -> None:
    storeys = sim.storeys
    assert storeys is not None
    made = generate_house_episodes(sim, np.random.default_rng(0))
    assert made.ign and made.ign[0].scene_id == "vlln/house_00001_2f/house_00001_2f.glb"
    crossing = []
    for episode in made.ign:
        start = storeys.level_of(episode.start_position[1])
        box = sim.house.instance(int(episode.instruction.instance_id[0])).box
        floor = storeys.floor_ys[storeys.level_under(box.min[1])]
        for vp in episode.goals[0].view_points:  # the 3-D box grown by 0.6 m, or its floor
            height = vp.position[1]
            assert box.min[1] - 0.6 <= height <= box.max[1] + 0.6 or height == floor
        if storeys.level_under(box.min[1]) != start:
            crossing.append(episode)
    assert len(crossing) >= 0.25 * len(made.ign)
    for episode in crossing[:: max(1, len(crossing) // 4)][:4]:
        goals = [vp.position for vp in episode.goals[0].view_points]
        field = sim.distance_field(goals)
        x, y, z = episode.start_position
        assert field.distance(x, z, y) == pytest.approx(episode.info["geodesic_distance"], abs=1e-3)
        follower = GreedyFollower(sim.nav, field, 0.25, sim.config.motion)
        sim.reset(AgentState((x, y, z), quaternion_to_yaw(episode.start_rotation)))
        for _ in range(500):
            action = follower.next_action(sim.state)
            if action == Action.STOP:
                break
            sim.move(action)
        px, py, pz = sim.state.position
        assert field.distance(px, pz, py) < 0.25
        assert storeys.level_of(py) != storeys.level_of(y)
        assert math.isfinite(field.distance(px, pz, py))
