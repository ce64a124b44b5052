"""The environment: the datasheet's promises on a real generated house."""

import math
from dataclasses import replace

import numpy as np
import pytest

from vlln.errors import ConfigError, EpisodeRefusedError
from vlln.oracle.knowledge import HouseIndex
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import Action
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.tasks.record import EndReason
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import REFUSAL_MESSAGE, Talk, TaskConfig, TaskType
from vlln.tasks.taxonomy import classify
from vlln.world.frame import yaw_of, yaw_to_quaternion
from vlln.world.model import ObjectInstance

SEED = 2


@pytest.fixture(scope="module")
def scenes() -> SceneCache:
    cache = SceneCache()
    yield cache
    cache.close()


def episode_for(
    scenes: SceneCache, target: ObjectInstance, start: tuple[float, float], yaw: float = 0.0
) -> Episode:
    sim = scenes.get(procedural_scene_id(SEED))
    points = view_points(sim.grid, target.box)
    goal = Goal(
        target.position,
        None,
        (*target.box.min, *target.box.max),
        tuple(ViewPoint((x, 0.0, z)) for x, z in points),
    )
    return Episode(
        "e0",
        procedural_scene_id(SEED),
        (start[0], 0.0, start[1]),
        tuple(yaw_to_quaternion(yaw)),
        target.category,
        (goal,),
        Instruction("iign", f"Search for the {target.category}.", (str(target.id),)),
    )


def _seen_from_its_room(sim: Simulator, inst: ObjectInstance) -> bool:
    """Whether the object has view points and all are in its own room: the goal region of
    an object by a wall also takes in floor behind the wall, where it cannot be seen."""
    points = view_points(sim.grid, inst.box)
    rooms = HouseIndex.build(sim.house).rooms_at(np.array(points).reshape(-1, 2))
    return bool(points) and bool((rooms == inst.room_id).all())


def ambiguous_target(scenes: SceneCache) -> tuple[ObjectInstance, ObjectInstance]:
    """A target and a same-category distractor more than 3 m apart, each with view points
    in its own room only."""
    sim = scenes.get(procedural_scene_id(SEED))
    for category in ("chair", "picture", "plant", "pillow", "cabinet"):
        found = [i for i in sim.house.instances_of(category) if _seen_from_its_room(sim, i)]
        for other in found[1:]:
            if found[0].box.distance_to(other.box) > 3.0:
                return found[0], other
    raise AssertionError("house has no ambiguous category")


def far_start(scenes: SceneCache, target: ObjectInstance) -> tuple[float, float]:
    sim = scenes.get(procedural_scene_id(SEED))
    field = sim.geodesic_field(view_points(sim.grid, target.box))
    rng = np.random.default_rng(0)
    while True:
        x, z = sim.grid.sample_navigable_point(rng, sim.grid.largest_component())
        if 3.0 < field.distance(x, z) < 30.0:
            return x, z


@pytest.mark.slow
def test_expert_actions_succeed_and_the_record_says_so(scenes: SceneCache) -> None:
    target, _ = ambiguous_target(scenes)
    env = NavigationEnv(
        [episode_for(scenes, target, far_start(scenes, target))],
        TaskConfig(task=TaskType.IGN),
        scenes,
        privileged=True,
    )
    obs, _ = env.reset(options={"episode_index": 0})
    assert {"rgb", "depth", "gps", "compass", "instance_ids", "expert_action"} <= set(obs)
    np.testing.assert_allclose(obs["gps"], 0.0, atol=1e-6)
    while True:
        obs, _, terminated, truncated, _ = env.step(obs["expert_action"])
        if terminated or truncated:
            break
    record = env.record("expert")
    assert terminated and record.end_reason == EndReason.STOP
    assert classify(record) == "success"
    assert record.stop_instance_id == target.id
    assert record.target_seen_step is not None
    assert record.path_length >= record.geodesic_start * 0.9


def test_unprivileged_agents_get_no_ids_and_gps_follows_the_start_frame(
    scenes: SceneCache,
) -> None:
    target, _ = ambiguous_target(scenes)
    start = far_start(scenes, target)
    yaw = 1.0
    env = NavigationEnv(
        [episode_for(scenes, target, start, yaw)], TaskConfig(task=TaskType.IGN), scenes
    )
    obs, _ = env.reset(options={"episode_index": 0})
    assert "instance_ids" not in obs and "expert_action" not in obs
    obs, *_ = env.step(Action.MOVE_FORWARD)
    moved = math.hypot(*obs["gps"])
    if moved > 0.2:  # not blocked: moving forward goes along -z of the start frame
        assert obs["gps"][1] < -0.2 and abs(obs["gps"][0]) < 0.05


def test_dialog_budget_and_talk_cap(scenes: SceneCache) -> None:
    target, _ = ambiguous_target(scenes)
    config = TaskConfig(task=TaskType.IIGN, dialog_budget=2, max_talk_actions=4)
    env = NavigationEnv(
        [episode_for(scenes, target, far_start(scenes, target))],
        config,
        scenes,
        oracle=RuleOracle(seed=0),
    )
    env.reset(options={"episode_index": 0})
    answers = []
    for _ in range(4):
        obs, _, terminated, truncated, _ = env.step(Talk("What color is it?"))
        answers.append(obs["oracle_answer"])
    assert answers[0] != REFUSAL_MESSAGE and answers[2] == REFUSAL_MESSAGE
    assert truncated and not terminated
    record = env.record("talker")
    assert record.end_reason == EndReason.TALK_CAP
    assert [turn.answered for turn in record.dialog] == [True, True, False, False]
    assert record.steps == 0  # TALK does not count toward the step cap


def test_garbage_outputs_are_failed_actions_not_stops(scenes: SceneCache) -> None:
    target, _ = ambiguous_target(scenes)
    env = NavigationEnv(
        [episode_for(scenes, target, far_start(scenes, target))],
        TaskConfig(task=TaskType.IGN, max_failed_actions=3),
        scenes,
    )
    env.reset(options={"episode_index": 0})
    for _ in range(3):
        _, _, terminated, truncated, _ = env.step("jump!")  # type: ignore[arg-type]
        assert not terminated
    record = env.record("broken")
    assert truncated and record.end_reason == EndReason.ERROR and record.failed_actions == 3
    assert record.error == "3 failed actions (invalid 3), the cap max_failed_actions"
    with pytest.raises(ConfigError, match="has ended"):
        env.step(Action.STOP)


def test_look_actions_have_their_own_cap(scenes: SceneCache) -> None:
    target, _ = ambiguous_target(scenes)
    env = NavigationEnv(
        [episode_for(scenes, target, far_start(scenes, target))],
        TaskConfig(task=TaskType.IGN, max_look_actions=5),
        scenes,
    )
    env.reset(options={"episode_index": 0})
    for _ in range(5):
        *_, truncated, _ = env.step(Action.LOOK_DOWN)
    record = env.record("looker")
    assert truncated and record.end_reason == EndReason.LOOK_CAP and record.steps == 0


def test_stopping_at_a_distractor_is_an_ambiguous_detection(scenes: SceneCache) -> None:
    target, distractor = ambiguous_target(scenes)
    sim = scenes.get(procedural_scene_id(SEED))
    # Stand at the distractor's nearest view point, facing it.
    cx, _, cz = distractor.position
    points = view_points(sim.grid, distractor.box)
    x, z = min(points, key=lambda p: math.hypot(p[0] - cx, p[1] - cz))
    yaw = yaw_of(cx - x, cz - z)
    env = NavigationEnv(
        [episode_for(scenes, target, (x, z), yaw)], TaskConfig(task=TaskType.IGN), scenes
    )
    env.reset(options={"episode_index": 0})
    env.step(Action.STOP)
    record = env.record("fooled")
    assert record.stop_instance_id is not None and record.stop_instance_id != target.id
    stopped = sim.house.instance(record.stop_instance_id)  # the distractor or its neighbour
    assert stopped.category == target.category
    assert record.geodesic_final > 1.0
    assert record.distractor_distance is not None and record.distractor_distance < 0.25
    assert classify(record) == "ambiguous_detection"


def test_a_stop_at_a_distractor_facing_away_is_still_ambiguous(scenes: SceneCache) -> None:
    target, distractor = ambiguous_target(scenes)
    sim = scenes.get(procedural_scene_id(SEED))
    cx, _, cz = distractor.position
    points = view_points(sim.grid, distractor.box)
    x, z = min(points, key=lambda p: math.hypot(p[0] - cx, p[1] - cz))
    away = yaw_of(x - cx, z - cz)  # the back to the distractor
    for task in (TaskType.IGN, TaskType.OBJECTNAV):
        env = NavigationEnv([episode_for(scenes, target, (x, z), away)], TaskConfig(task), scenes)
        env.reset(options={"episode_index": 0})
        env.step(Action.STOP)
        record = env.record("turned")
        assert record.stop_instance_id != distractor.id
        if task == TaskType.IGN:
            assert record.distractor_distance is not None and record.distractor_distance < 0.25
            assert classify(record) == "ambiguous_detection"
        else:  # every instance of the category is a goal: none is a distractor
            assert record.distractor_distance is None
            assert classify(record) != "ambiguous_detection"
    # Not stopped: no stop facts.
    env.reset(options={"episode_index": 0})
    env.step(Action.TURN_LEFT)
    record = env.record("unfinished")
    assert record.end_reason == EndReason.ERROR and record.distractor_distance is None


def test_ign_answers_questions_when_given_a_budget_objectnav_never(scenes: SceneCache) -> None:
    target, _ = ambiguous_target(scenes)
    episode = episode_for(scenes, target, far_start(scenes, target))
    assert TaskConfig(task=TaskType.IGN).dialog_budget == 0  # the default stays no dialog
    with pytest.raises(ConfigError, match="ign with a dialog budget needs an oracle"):
        NavigationEnv([episode], TaskConfig(task=TaskType.IGN, dialog_budget=2), scenes)
    with pytest.raises(ConfigError, match="objectnav has no dialog"):
        TaskConfig(task=TaskType.OBJECTNAV, dialog_budget=2)
    for task, budget in ((TaskType.IGN, 2), (TaskType.OBJECTNAV, 0)):
        config = TaskConfig(task=task, dialog_budget=budget)
        env = NavigationEnv([episode], config, scenes, oracle=RuleOracle(seed=0))
        obs, _ = env.reset(options={"episode_index": 0})
        assert obs["questions_left"] == budget
        obs, *_ = env.step(Talk("What color is it?"))
        answered = task == TaskType.IGN
        assert (obs["oracle_answer"] != REFUSAL_MESSAGE) == answered
        record = env.record("talker")
        assert record.budget == budget
        assert [turn.answered for turn in record.dialog] == [answered]


def test_a_start_or_goals_off_the_only_storey_refuse_the_episode(scenes: SceneCache) -> None:
    """A one-storey scene never takes a start or view points from another storey's height
    onto its floor (an episode made for a scan with an upper floor)."""
    target, _ = ambiguous_target(scenes)
    x, z = far_start(scenes, target)
    made = episode_for(scenes, target, (x, z))
    upstairs = replace(made, start_position=(x, 2.8, z))
    lifted = replace(
        made,
        goals=tuple(
            replace(
                goal,
                view_points=tuple(
                    ViewPoint((p[0], 2.8, p[2])) for p in (vp.position for vp in goal.view_points)
                ),
            )
            for goal in made.goals
        ),
    )
    cx, _, cz = target.box.center
    blocked = replace(made, start_position=(cx, 0.0, cz))  # inside the target
    expected = {
        "upstairs": "its start height 2.80 m is on no storey of the scene (floors at 0.00 m)",
        "lifted": f"its {len(made.goals[0].view_points)} goal view points are on no storey",
        "blocked": "is not navigable on storey 0 (the nearest navigable point is",
    }
    for name, episode in (("upstairs", upstairs), ("lifted", lifted), ("blocked", blocked)):
        env = NavigationEnv(
            [replace(episode, episode_id=name)], TaskConfig(task=TaskType.IGN), scenes
        )
        with pytest.raises(EpisodeRefusedError) as refused:
            env.reset(options={"episode_index": 0})
        assert str(refused.value).startswith(f"episode {name} in {made.scene_id} is refused: ")
        assert expected[name] in refused.value.reason
