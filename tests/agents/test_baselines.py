import math

import numpy as np
import pytest

from vlln.agents.expert import ExpertAgent
from vlln.agents.random_agent import RandomAgent
from vlln.agents.registry import AGENTS, make_agent
from vlln.errors import ConfigError
from vlln.sim.agent import Action, MotionConfig
from vlln.sim.camera import CameraSpec
from vlln.sim.viewpoints import view_points
from vlln.tasks.env import EpisodeInfo, NavigationEnv
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.taxonomy import classify
from vlln.world.frame import yaw_to_quaternion


def _info(episode_id: str) -> EpisodeInfo:
    return EpisodeInfo(
        episode_id,
        TaskType.IIGN,
        "Search for the chair.",
        "chair",
        CameraSpec(),
        MotionConfig(),
        0,
        500,
    )


def test_registry_makes_every_agent_and_names_the_valid_ones_on_error() -> None:
    for name in AGENTS:
        agent = make_agent(name, 1)
        assert agent.name == name
    assert make_agent("expert", 0).privileged and not make_agent("random", 0).privileged
    with pytest.raises(ConfigError) as error:
        make_agent("walker", 0)
    message = str(error.value)
    assert "walker" in message
    assert all(name in message for name in ("random", "expert", "frontier"))


def _actions(agent: RandomAgent, episode_id: str, n: int) -> list[Action]:
    agent.reset(_info(episode_id))
    return [agent.act({}) for _ in range(n)]  # type: ignore[misc]


def test_random_agent_is_seeded_per_agent_and_episode() -> None:
    first = _actions(RandomAgent(seed=5), "a", 200)
    assert first == _actions(RandomAgent(seed=5), "a", 200)
    assert first != _actions(RandomAgent(seed=6), "a", 200)
    assert first != _actions(RandomAgent(seed=5), "b", 200)


def test_random_agent_moves_uniformly_and_rarely_stops() -> None:
    actions = _actions(RandomAgent(seed=0), "x", 5000)
    counts = {a: actions.count(a) for a in Action}
    assert 50 <= counts[Action.STOP] <= 160  # p = 0.02
    for move in (Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT):
        assert abs(counts[move] / 5000 - 0.98 / 3) < 0.03
    assert counts[Action.LOOK_UP] == counts[Action.LOOK_DOWN] == 0
    with pytest.raises(ConfigError, match="reset"):
        RandomAgent(seed=0).act({})


@pytest.mark.slow
def test_expert_reaches_the_goal_of_a_generated_episode() -> None:
    scenes = SceneCache()
    scene_id = procedural_scene_id(1)
    sim = scenes.get(scene_id)
    target = sim.house.instances_of("chair")[0]
    points = view_points(sim.grid, target.box)
    x, z = sim.grid.sample_navigable_point(np.random.default_rng(3), sim.grid.largest_component())
    box = target.box
    episode = Episode(
        episode_id="0",
        scene_id=scene_id,
        start_position=(x, 0.0, z),
        start_rotation=tuple(yaw_to_quaternion(0.3)),  # type: ignore[arg-type]
        object_category="chair",
        goals=(
            Goal(
                target.position,
                None,
                (*box.min, *box.max),
                tuple(ViewPoint((a, 0.0, b)) for a, b in points),
            ),
        ),
        instruction=Instruction("iign", "Search for the chair.", (str(target.id),), None),
    )
    env = NavigationEnv([episode], TaskConfig(task=TaskType.IGN), scenes, privileged=True)
    observation, _ = env.reset(options={"episode_index": 0})
    expert = ExpertAgent(seed=0)
    expert.reset(env.episode_info())
    for _ in range(600):
        observation, _, terminated, truncated, _ = env.step(expert.act(observation))
        if terminated or truncated:
            break
    record = env.record("expert")
    assert classify(record) == "success"
    assert record.path_length >= record.geodesic_start - 0.25 - 1e-6
    assert record.path_length <= record.geodesic_start + 2.0  # close to the shortest path
    assert math.isfinite(record.geodesic_start) and record.geodesic_start > 0.0


def test_expert_needs_the_expert_action() -> None:
    with pytest.raises(ConfigError, match="privileged"):
        ExpertAgent(seed=0).act({"gps": np.zeros(2)})
