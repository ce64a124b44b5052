"""The dialog decision as a Gymnasium environment: spaces, rewards, leaving an episode, and
training houses only."""

from __future__ import annotations

import math

import gymnasium
import pytest

from tests.agents import world
from vlln.errors import ConfigError
from vlln.gym.dialog import DialogEnv, training_episodes
from vlln.sim.simulator import Simulator
from vlln.tasks.metrics import success


def two_room_env(lam: float) -> DialogEnv:
    """Two episodes of the two-room house; the worker renders with a simulator of its own."""
    sim = Simulator(world.two_room_house())
    episodes = [
        world.episode(sim, world.BLUE_CHAIR, (3.5, 2.0), -math.pi / 2),
        world.episode(sim, world.RED_CHAIR, (2.5, 2.0), -math.pi / 2),
    ]
    return DialogEnv(
        episodes, lam=lam, scenes=lambda: world.OneScene(Simulator(world.two_room_house()))
    )


def play(env: DialogEnv, action: int) -> tuple[float, dict[str, object]]:
    """One whole episode with a constant action: its summed reward and last info."""
    observation, _ = env.reset()
    total = 0.0
    while True:
        assert env.observation_space.contains(observation)
        observation, reward, terminated, truncated, info = env.step(action)
        total += reward
        if terminated or truncated:
            return total, info


def test_spaces_and_a_whole_episode_that_never_asks() -> None:
    env = two_room_env(lam=0.25)
    try:
        assert env.observation_space.shape == (18,)
        assert isinstance(env.action_space, gymnasium.spaces.Discrete) and env.action_space.n == 4
        total, info = play(env, 0)
        record = info["record"]
        assert record.dialog == []  # type: ignore[attr-defined]
        assert total == float(success(record))  # type: ignore[arg-type]
    finally:
        env.close()
    assert env._worker is None


def test_each_question_costs_lambda_and_success_pays_one() -> None:
    env = two_room_env(lam=0.25)
    try:
        total, info = play(env, 1)  # the colour, wherever it may be asked: once
        record = info["record"]
        asked = len(record.dialog)  # type: ignore[attr-defined]
        assert asked == 1
        assert total == pytest.approx(float(success(record)) - 0.25 * asked)  # type: ignore[arg-type]
    finally:
        env.close()


def test_a_reset_mid_episode_leaves_it_and_starts_the_next() -> None:
    env = two_room_env(lam=0.0)
    try:
        env.reset()
        observation, _ = env.reset()
        assert env.observation_space.contains(observation)
        assert env.played >= 1
    finally:
        env.close()


@pytest.mark.parametrize("split", ["test", "test500"])
def test_the_test_houses_are_never_trained_on(split: str) -> None:
    with pytest.raises(ConfigError, match="never on"):
        training_episodes(split, 1, "small")
