"""The random baseline: the floor every agent must clear."""

from __future__ import annotations

import zlib

import numpy as np

from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.spec import AgentOutput

_MOVES = (Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT)


class RandomAgent:
    """Forward, left or right uniformly at random; STOP with a small probability per step.

    The generator is seeded by the agent's seed and the episode id, so an episode plays the
    same way whatever order episodes are run in.
    """

    name = "random"
    privileged = False
    snapshottable = True  # see vlln.eval.sweep

    def __init__(self, seed: int = 0, stop_probability: float = 0.02) -> None:
        if not 0.0 <= stop_probability <= 1.0:
            raise ConfigError(f"stop_probability must be in [0, 1], got {stop_probability}")
        self.seed = int(seed)
        self.stop_probability = stop_probability
        self._rng: np.random.Generator | None = None

    def reset(self, episode: EpisodeInfo) -> None:
        self._rng = np.random.default_rng([self.seed, zlib.crc32(episode.episode_id.encode())])

    def act(self, observation: Observation) -> AgentOutput:
        if self._rng is None:
            raise ConfigError("call reset(episode_info) before act()")
        if self._rng.random() < self.stop_probability:
            return Action.STOP
        return _MOVES[int(self._rng.integers(len(_MOVES)))]
