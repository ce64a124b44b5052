import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.agents import world
from tests.sim import scenes
from vlln.agents.registry import make_agent
from vlln.agents.vlfm import VlfmAgent
from vlln.agents.vlfm.build import DEFAULT_OUT, build, main
from vlln.agents.vlfm.prior import shipped_prior
from vlln.sim.simulator import Simulator
from vlln.tasks.spec import TaskType
from vlln.tasks.splits import split_of
from vlln.tasks.taxonomy import classify
from vlln.world.mesh import Mesh
from vlln.world.model import Attributes, Box3, House, HouseGeometry, ObjectInstance, Room

CHAIR = 1


@pytest.fixture(scope="module")
def one_chair() -> Simulator:
    """Rooms A and B of the two-room house with a single chair, in room A's east end."""
    box = Box3((4.75, 0.0, 0.75), (5.25, 0.9, 1.25))
    chair = ObjectInstance(CHAIR, "chair", "chair", Attributes(color="red"), "a chair", box, 0)
    mesh = [scenes.l_shaped_rooms(), scenes.box_object(CHAIR, 5.0, 1.0, (0.5, 0.9, 0.5))]
    rooms = [
        Room(0, "living room", ((0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (0.0, 4.0))),
        Room(1, "bedroom", ((0.0, 4.0), (3.0, 4.0), (3.0, 9.0), (0.0, 9.0))),
    ]
    house = House("one_chair", rooms, [], [chair], geometry=HouseGeometry(Mesh.concatenate(mesh)))
    return Simulator(house)


@pytest.mark.slow
def test_the_prior_is_deterministic_and_learnt_from_training_houses(tmp_path: Path) -> None:
    first, second = tmp_path / "a.json", tmp_path / "b.json"
    assert main(["--houses", "2", "--preset", "small", "--out", str(first)]) == 0
    assert main(["--houses", "2", "--preset", "small", "--out", str(second)]) == 0
    assert first.read_bytes() == second.read_bytes()
    prior = json.loads(first.read_text())
    assert prior == build(2, "small")
    assert set(prior["source"]) == {"preset", "split", "house_seeds"}
    # a bed is in bedrooms, and a pillow is far likelier in a room with a bed than in any
    assert max(prior["in_room"]["bed"], key=prior["in_room"]["bed"].get) == "bedroom"
    shipped = json.loads(DEFAULT_OUT.read_text())
    assert shipped["source"]["preset"] == "mp3d" and len(shipped["source"]["house_seeds"]) == 61
    assert {split_of(seed) for seed in shipped["source"]["house_seeds"]} == {"train"}
    loaded = shipped_prior()
    assert loaded.frame_value("pillow", {"bed": 500.0}) > 2 * loaded.frame_value("pillow", {})


def test_with_nothing_detected_the_value_map_is_the_room_prior(one_chair: Simulator) -> None:
    # From room B facing the back wall, the opening scan sees no object at all.
    episode = world.episode(one_chair, CHAIR, (1.5, 8.0), math.pi)
    env = world.make_env(one_chair, [episode], TaskType.OBJECTNAV)
    agent = VlfmAgent(seed=2)
    observation, _ = env.reset(options={"episode_index": 0})
    agent.reset(env.episode_info())
    for _ in range(13):
        assert agent.seen_categories() == {}
        observation, *_ = env.step(agent.act(observation))
    seen = agent.values.confidence > 0
    assert seen.sum() > 500  # the whole room was painted ...
    prior = agent.prior.frame_value("chair", {})
    assert prior == pytest.approx(agent.prior.room_value("chair", {}))
    np.testing.assert_allclose(agent.values.value[seen], prior, rtol=1e-5)  # ... with the prior


def test_what_is_seen_changes_the_value_map() -> None:
    sim = Simulator(world.two_room_house())
    episode = world.episode(sim, world.RED_CHAIR, (2.5, 2.0), -math.pi / 2)
    env = world.make_env(sim, [episode], TaskType.OBJECTNAV)
    agent = VlfmAgent(seed=2)
    observation, _ = env.reset(options={"episode_index": 0})
    agent.reset(env.episode_info())
    observation, *_ = env.step(agent.act(observation))
    assert set(agent.seen_categories()) == {"chair"}
    seen = agent.values.confidence > 0
    assert not np.allclose(agent.values.value[seen], agent.prior.frame_value("chair", {}))


def test_vlfm_finds_an_objectnav_target_in_another_room(one_chair: Simulator) -> None:
    episode = world.episode(one_chair, CHAIR, (1.5, 8.0), math.pi)
    env = world.make_env(one_chair, [episode], TaskType.OBJECTNAV)
    world.play(env, make_agent("vlfm", 2))
    record = env.record("vlfm")
    assert classify(record) == "success"
    assert record.dialog == []
