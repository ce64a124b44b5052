"""The environment's pixel goals and recorded failures on a real generated house."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from tests.agents.world import RED_CHAIR, episode, two_room_house
from tests.agents.world import make_env as make_world_env
from tests.tasks.test_env import ambiguous_target, episode_for, far_start
from vlln.sim.agent import Action
from vlln.sim.follower import GreedyFollower
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv
from vlln.tasks.record import EndReason, EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import FailedOutput, PixelGoal, TaskConfig, TaskType
from vlln.tasks.waypoint import WAYPOINT_RADIUS, WAYPOINT_REACH, waypoint_field
from vlln.world.frame import heading_vector


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    cache = SceneCache()
    yield cache
    cache.close()


def make_env(scenes: SceneCache, max_failed: int = 20) -> NavigationEnv:
    target, _ = ambiguous_target(scenes)
    config = TaskConfig(task=TaskType.IGN, max_failed_actions=max_failed)
    return NavigationEnv([episode_for(scenes, target, far_start(scenes, target))], config, scenes)


def visible_floor_pixel(env: NavigationEnv) -> tuple[int, int, float, float]:
    """A pixel of the current (tilted) frame that shows navigable floor 1.5-3 m ahead."""
    sim = env.sim
    spec = sim.config.camera
    state = sim.state
    fx, fy, cx, cy = spec.intrinsics()
    depth = env._frame.depth
    for ahead in np.linspace(3.0, 1.2, 10):
        dx, dz = heading_vector(state.yaw)
        gx, gz = state.position[0] + ahead * dx, state.position[2] + ahead * dz
        if not sim.grid.is_navigable(gx, gz):
            continue
        view = spec.view_matrix(state.position, state.yaw, state.tilt)
        local = view @ np.array([gx, 0.0, gz, 1.0])
        z_depth = -float(local[2])
        col, row = round(cx + fx * local[0] / z_depth), round(cy - fy * local[1] / z_depth)
        if 0 <= row < spec.height and abs(float(depth[row, col]) - z_depth) < 0.05:
            return col, row, gx, gz
    raise LookupError("no visible floor ahead")


def turn_until_floor_is_visible(env: NavigationEnv) -> tuple[int, int, float, float]:
    for _ in range(12):
        env.step(Action.LOOK_DOWN)
        try:
            return visible_floor_pixel(env)
        except LookupError:
            env.step(Action.LOOK_UP)
            env.step(Action.TURN_LEFT)
    raise AssertionError("no heading shows floor ahead")


@pytest.mark.slow
def test_a_pixel_goal_levels_the_camera_and_the_waypoint_leads_to_its_floor_point(
    scenes: SceneCache,
) -> None:
    env = make_env(scenes)
    observation, _ = env.reset(options={"episode_index": 0})
    assert observation["waypoint_action"] is None
    col, row, gx, gz = turn_until_floor_is_visible(env)
    looks_before = env._looks
    observation, *_ = env.step(PixelGoal(col, row))
    assert observation["tilt"] == 0.0
    assert env._looks == looks_before  # the LOOK_DOWN before it was counted
    walked = 0
    while observation["waypoint_action"] is not None:
        assert walked < 40
        observation, *_ = env.step(observation["waypoint_action"])
        walked += 1
    assert walked >= 4
    x, _, z = env.sim.state.position
    assert math.hypot(x - gx, z - gz) < 0.25 + 0.1
    record = env.record("test")
    assert f"PIXEL:{col},{row}" in record.actions
    assert record.failed_actions == 0 and record.failures == {}


def test_another_action_ends_the_walk_to_a_pixel_goal(scenes: SceneCache) -> None:
    env = make_env(scenes)
    env.reset(options={"episode_index": 0})
    col, row, _, _ = turn_until_floor_is_visible(env)
    observation, *_ = env.step(PixelGoal(col, row))
    assert observation["waypoint_action"] is not None
    observation, *_ = env.step(Action.LOOK_DOWN)
    assert observation["waypoint_action"] is None
    env.step(Action.LOOK_UP)
    looks = env._looks
    observation, *_ = env.step(PixelGoal(320, 479))  # on a level frame: counted as a look
    assert env._looks == looks + 1 and env._failed == 0
    assert observation["waypoint_action"] is not None


def test_failed_outputs_waste_a_step_level_the_camera_and_are_counted_by_kind(
    scenes: SceneCache,
) -> None:
    env = make_env(scenes, max_failed=4)
    env.reset(options={"episode_index": 0})
    start = env.sim.state.position
    env.step(Action.LOOK_DOWN)
    observation, *_ = env.step(FailedOutput("parse", "no leading tag"))
    assert observation["tilt"] == 0.0
    assert env.sim.state.position == start
    env.step(FailedOutput("server", "HTTP 500"))
    env.step(PixelGoal(5000, 10))  # outside the image: no goal
    *_, terminated, truncated, info = env.step(FailedOutput("parse", "two tags"))
    assert truncated and not terminated
    assert info["steps"] == 4
    record = EpisodeRecord.from_json(env.record("test").to_json())
    assert record.end_reason == EndReason.ERROR
    assert record.failed_actions == 4
    assert record.failures == {"parse": 2, "server": 1, "goal": 1}
    assert record.actions[-4:] == [
        "FAILED:parse",
        "FAILED:server",
        "FAILED:goal:5000,10",
        "FAILED:parse",
    ]


def test_records_written_before_failure_kinds_still_read() -> None:
    env_free = EpisodeRecord.from_json(
        {
            "episode_id": "e",
            "scene_id": "s",
            "task": "iign",
            "agent": "a",
            "budget": 0,
            "object_category": "chair",
            "target_ids": [1],
            "end_reason": "stop",
            "steps": 1,
            "geodesic_start": 1.0,
            "geodesic_trace": [1.0],
            "path_length": 0.0,
            "stop_instance_id": None,
            "stop_instance_category": None,
            "target_seen_step": None,
        }
    )
    assert env_free.failures == {} and env_free.model_calls == []


def test_a_pixel_goal_the_agent_already_stands_on_is_a_failed_goal() -> None:
    """Facing a wall 0.3 m away, the wall's pixel snaps to floor within the follower's radius:
    a goal that would not move the agent, which a model naming it again would loop on."""
    with Simulator(two_room_house()) as sim:
        start = episode(sim, RED_CHAIR, (3.0, 0.3), 0.0)  # room A's south wall lies at z = 0
        env = make_world_env(sim, [start], TaskType.IGN)
        env.reset(options={"episode_index": 0})
        env.step(Action.LOOK_DOWN)
        spec = sim.config.camera
        col, row = spec.width // 2, spec.height // 2
        observation, *_ = env.step(PixelGoal(col, row))
        assert observation["waypoint_action"] is None and observation["tilt"] == 0.0
        record = env.record("test")
        assert record.actions[-1] == f"FAILED:goal:{col},{row}"
        assert record.failures == {"goal": 1}


def test_a_waypoint_field_is_bounded_only_where_that_leaves_the_walk_unchanged(
    scenes: SceneCache,
) -> None:
    env = make_env(scenes)
    env.reset(options={"episode_index": 0})
    sim, state = env.sim, env.sim.state
    x, _, z = state.position
    rng = np.random.default_rng(3)
    near = far = None
    while near is None or far is None:
        point = sim.grid.sample_navigable_point(rng, sim.grid.largest_component())
        d = sim.distance_field([point]).distance(x, z)
        if 1.0 < d < WAYPOINT_REACH - 0.5:
            near = point
        elif d > WAYPOINT_REACH + 1.0:
            far = point
    whole = sim.distance_field([far])
    assert waypoint_field(sim, far, state) is whole  # beyond reach: the whole house's field
    bounded = waypoint_field(sim, near, state)
    whole = sim.distance_field([near])
    assert bounded is not whole and np.isinf(bounded.values).sum() > np.isinf(whole.values).sum()
    walks = []
    for field in (bounded, whole):
        follower = GreedyFollower(sim.grid, field, WAYPOINT_RADIUS, sim.config.motion)
        sim.reset(state)
        actions = [follower.next_action(sim.state)]
        while actions[-1] != Action.STOP and len(actions) < 60:
            sim.step(actions[-1])
            actions.append(follower.next_action(sim.state))
        walks.append(actions)
    assert walks[0] == walks[1] and walks[0][-1] == Action.STOP
