"""The simulator on a generated house: determinism end to end, motion and the field cache."""

from pathlib import Path

import numpy as np
import pytest

from vlln.errors import ConfigError
from vlln.sim.agent import Action, AgentState
from vlln.sim.simulator import Simulator
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House
from vlln.world.scene_summary import export_scene_summary

SMALL = HouseParameters(min_rooms=4, max_rooms=5, min_area=60.0, max_area=90.0)


@pytest.fixture(scope="module")
def sim() -> Simulator:
    with Simulator(generate_house(11, SMALL)) as simulator:
        yield simulator


def start_state(sim: Simulator, seed: int) -> AgentState:
    x, z = sim.grid.sample_navigable_point(np.random.default_rng(seed))
    return AgentState((x, sim.grid.floor_y, z), 0.5, 0.0)


def test_same_seed_gives_identical_export_and_frames(tmp_path: Path) -> None:
    first, second = generate_house(5, SMALL), generate_house(5, SMALL)
    a = export_scene_summary(first, tmp_path / "a")
    b = export_scene_summary(second, tmp_path / "b")
    for name in ("object_dict.json", "region_dict.json"):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    with Simulator(first) as sim_a, Simulator(second) as sim_b:
        state = start_state(sim_a, 0)
        frame_a, frame_b = sim_a.render(state), sim_b.render(state)
    assert frame_a.rgb.tobytes() == frame_b.rgb.tobytes()
    assert frame_a.depth.tobytes() == frame_b.depth.tobytes()
    assert frame_a.instance_ids.tobytes() == frame_b.instance_ids.tobytes()


def test_steps_keep_the_agent_navigable_and_frames_change(sim: Simulator) -> None:
    first = sim.reset(start_state(sim, 1))
    rng = np.random.default_rng(2)
    moved = False
    for action in rng.choice([Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT], 60):
        observation = sim.step(Action(int(action)))
        x, _, z = observation.state.position
        assert sim.grid.is_navigable(x, z)
        moved |= not np.array_equal(observation.frame.rgb, first.frame.rgb)
    assert moved


def test_reset_off_the_floor_names_the_nearest_navigable_point(sim: Simulator) -> None:
    with pytest.raises(ConfigError, match="nearest navigable point"):
        sim.reset(AgentState((-100.0, 0.0, -100.0), 0.0, 0.0))


def test_geodesic_fields_are_cached_per_goal_set(sim: Simulator) -> None:
    goal = sim.grid.sample_navigable_point(np.random.default_rng(3))
    assert sim.geodesic_field([goal]) is sim.geodesic_field([goal])
    other = sim.grid.sample_navigable_point(np.random.default_rng(4))
    assert sim.geodesic_field([other]) is not sim.geodesic_field([goal])


def test_a_house_without_geometry_is_refused() -> None:
    house = House("empty", rooms=[], doors=[], instances=[])
    with pytest.raises(ConfigError, match="no geometry"):
        Simulator(house)
