import math

import pytest

from tests.agents import world
from tests.sim import scenes
from vlln.agents.frontier import FrontierAgent, FrontierConfig
from vlln.agents.registry import make_agent
from vlln.errors import ConfigError
from vlln.eval.play import play_episode
from vlln.eval.sweep import play_sweep
from vlln.sim.agent import Action, MotionConfig
from vlln.sim.camera import CameraSpec
from vlln.sim.simulator import Simulator
from vlln.tasks.env import EpisodeInfo
from vlln.tasks.record import StopReason
from vlln.tasks.spec import Talk, TaskType
from vlln.tasks.taxonomy import classify
from vlln.world.mesh import Mesh
from vlln.world.model import Attributes, Box3, House, HouseGeometry, ObjectInstance, Room


@pytest.fixture(scope="module")
def sim() -> Simulator:
    return Simulator(world.two_room_house())


def test_ign_goes_to_the_described_chair_in_view(sim: Simulator) -> None:
    # Start in room A looking east, the red chair ahead, the blue one behind the door.
    episode = world.episode(sim, world.RED_CHAIR, (2.5, 2.0), -math.pi / 2, "Find the red chair.")
    env = world.make_env(sim, [episode], TaskType.IGN)
    actions = world.play(env, FrontierAgent(seed=3))
    record = env.record("frontier")
    assert actions[-1] == Action.STOP
    assert classify(record) == "success"
    assert record.stop_instance_id == world.RED_CHAIR  # it stopped facing the chair


def test_ign_explores_past_a_chair_of_the_wrong_colour(sim: Simulator) -> None:
    episode = world.episode(
        sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2, "Search for the blue chair."
    )
    env = world.make_env(sim, [episode], TaskType.IGN)
    world.play(env, FrontierAgent(seed=3))
    record = env.record("frontier")
    assert classify(record) == "success"
    assert record.steps > 20  # it had to find the door first


def test_iign_without_dialog_takes_the_first_chair_and_with_dialog_the_right_one(
    sim: Simulator,
) -> None:
    episode = world.episode(sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2)
    alone = world.make_env(sim, [episode], TaskType.IIGN, budget=0)
    agent = FrontierAgent(seed=3)
    world.play(alone, agent)
    record = alone.record("frontier", stop_reason=agent.stop_reason())
    assert record.stop_reason == StopReason.CANDIDATE  # it took the red chair for the target
    assert classify(record) == "ambiguous_detection"

    talking = world.make_env(sim, [episode], TaskType.IIGN, budget=5)
    actions = world.play(talking, FrontierAgent(seed=3))
    record = talking.record("frontier")
    assert classify(record) == "success"
    questions = [a.text for a in actions if isinstance(a, Talk)]
    assert questions[0].startswith("What")  # the colour question comes first
    assert any(q.startswith("Is this") for q in questions)
    assert len(questions) <= 5


def test_refusals_are_handled_and_the_budget_is_never_exceeded(sim: Simulator) -> None:
    episode = world.episode(sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2)
    env = world.make_env(sim, [episode], TaskType.IIGN, budget=1)
    world.play(env, FrontierAgent(seed=3))
    record = env.record("frontier")
    answered = [turn.answered for turn in record.dialog]
    # One answer, then at most one refused question: the refusal closes the dialog.
    assert answered[:1] == [True] and answered[1:] in ([], [False])
    assert record.end_reason == "stop"


def test_same_seed_same_actions(sim: Simulator) -> None:
    episode = world.episode(sim, world.BLUE_CHAIR, (4.5, 1.0), math.pi)
    runs = []
    for _ in range(2):
        env = world.make_env(sim, [episode], TaskType.IIGN, budget=5)
        runs.append(world.play(env, FrontierAgent(seed=11)))
    assert runs[0] == runs[1]


def test_ign_with_a_budget_asks_before_stopping_but_not_the_stated_colour(sim: Simulator) -> None:
    episode = world.episode(
        sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2, "Search for the blue chair."
    )
    env = world.make_env(sim, [episode], TaskType.IGN, budget=5)
    actions = world.play(env, FrontierAgent(seed=3))
    record = env.record("frontier")
    assert classify(record) == "success"
    questions = [turn.question for turn in record.dialog]
    assert questions and all(turn.answered for turn in record.dialog)
    assert any(q.startswith("Is this") for q in questions)
    assert not any(q.startswith("What") for q in questions)  # the instruction said blue
    assert sum(isinstance(a, Talk) for a in actions) == len(questions)


def test_noisy_detector_same_seed_same_actions(sim: Simulator) -> None:
    episode = world.episode(sim, world.BLUE_CHAIR, (4.5, 1.0), math.pi)
    runs = []
    for seed in (11, 11):
        env = world.make_env(sim, [episode], TaskType.IIGN, budget=5)
        runs.append(world.play(env, FrontierAgent(seed=seed, detector="noisy")))
    assert runs[0] == runs[1]
    with pytest.raises(ConfigError, match="truth, noisy"):
        FrontierAgent(detector="perfect")


def test_needs_reset_and_a_privileged_environment() -> None:
    agent = FrontierAgent(seed=0)
    with pytest.raises(ConfigError, match="reset"):
        agent.act({})
    info = EpisodeInfo(
        "0", TaskType.IIGN, "Search for the chair.", "chair", CameraSpec(), MotionConfig(), 5, 500
    )
    with pytest.raises(ConfigError, match="privileged"):
        agent.reset(info)


def hidden_chair_house() -> Simulator:
    """One room; the only chair stands inside a closed wardrobe, where no camera can see it."""
    wardrobe = ObjectInstance(
        3, "wardrobe", "wardrobe", Attributes(color="brown"), "a brown wardrobe",
        Box3((0.05, 0.0, 0.05), (1.05, 2.0, 1.05)), 0,
    )  # fmt: skip
    chair = ObjectInstance(
        4, "chair", "chair", Attributes(color="red"), "a red chair",
        Box3((0.3, 0.0, 0.3), (0.8, 0.9, 0.8)), 0,
    )  # fmt: skip
    parts = [scenes.empty_room()]
    for inst in (wardrobe, chair):
        x, _, z = inst.box.center
        parts.append(scenes.box_object(inst.id, x, z, inst.box.size))
    room = Room(0, "bedroom", ((0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (0.0, 4.0)))
    geometry = HouseGeometry(Mesh.concatenate(parts))
    return Simulator(House("hidden", [room], [], [wardrobe, chair], geometry=geometry))


def test_nothing_left_to_explore_is_recorded_and_is_an_exploration_failure() -> None:
    sim = hidden_chair_house()
    episode = world.episode(sim, 4, (4.5, 2.0), 0.0)
    env = world.make_env(sim, [episode], TaskType.IIGN, budget=0)
    record = play_episode(env, FrontierAgent(seed=3), "frontier")
    assert record.end_reason == "stop" and record.stop_reason == StopReason.EXPLORED
    assert record.target_seen_step is None and record.geodesic_final > 1.0
    assert record.distractor_distance is None  # the only chair is the target
    assert classify(record) == "exploration_failure"
    # The budget sweep records the reason at every budget too.
    env = world.make_env(sim, [episode], TaskType.IIGN, budget=2)
    swept = play_sweep(env, FrontierAgent(seed=3), "frontier", [0, 2])
    assert [r.stop_reason for r in swept.values()] == [StopReason.EXPLORED] * 2
    # Budget 0 went on from a copy taken at the refused question.
    assert [t.answered for t in swept[0].dialog] == [False]
    assert [t.answered for t in swept[2].dialog] == [True]


def test_fbe_never_asks_and_otherwise_plays_like_the_frontier_agent(sim: Simulator) -> None:
    episode = world.episode(sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2)
    env = world.make_env(sim, [episode], TaskType.IIGN, budget=5)
    actions = world.play(env, make_agent("fbe", 3))
    record = env.record("fbe")
    assert not any(isinstance(a, Talk) for a in actions) and record.dialog == []
    assert classify(record) == "ambiguous_detection"  # with no question, the red chair
    silent = world.make_env(sim, [episode], TaskType.IIGN, budget=0)
    world.play(silent, FrontierAgent(seed=3, config=FrontierConfig(asks=False)))
    assert silent.record("frontier").positions == record.positions
    # With the budget, the asking agent's questions change its course.
    talking = world.make_env(sim, [episode], TaskType.IIGN, budget=5)
    world.play(talking, FrontierAgent(seed=3))
    assert talking.record("frontier").positions != record.positions
