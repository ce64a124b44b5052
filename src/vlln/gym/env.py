"""The navigation environment as a Gymnasium environment (:class:`VllnEnv`).

Datasheet
---------
* **Ids**: ``vlln/IIGN-v0``, ``vlln/IGN-v0``, ``vlln/ObjectNav-v0`` (registered by importing
  :mod:`vlln.gym`; ``gymnasium.make("vlln.gym:vlln/IIGN-v0")`` imports it for you).
* **Action space**: ``Dict(action=Discrete(7), question=Text(1024))``. ``action`` 0-5 are
  :class:`vlln.sim.agent.Action` (STOP, MOVE_FORWARD 0.25 m, TURN_LEFT/RIGHT 30°, LOOK_UP/DOWN
  30°); 6 is TALK, which asks ``question`` (ignored for the other actions). A bare integer is
  accepted for the motion actions.
* **Observation space**: ``Dict`` with ``rgb`` Box(H, W, 3) uint8, ``depth`` Box(H, W) float32
  metres (0 to the camera's ``max_depth``), ``gps`` Box(2,) float32 metres from the start in
  the start's frame, ``height`` Box(1,) float32 metres of the feet above the start's (it
  changes only on stairs), ``compass`` and ``tilt`` Box(1,) float32 radians, ``instruction``
  Text, ``oracle_answer`` Text (the answer to a TALK on the step right after it, else ""),
  ``questions_left`` Discrete(budget + 1). With ``privileged=True`` also ``instance_ids``
  Box(H, W) int32 and ``expert_action`` Discrete(6) (the shortest-path follower's action).
* **Reward**: decrease of the geodesic distance to the nearest goal view point, +2.5 on success.
* **Termination**: STOP ends the episode (``terminated``); ``truncated`` at ``max_steps``
  counted steps or at the LOOK/TALK caps (see :mod:`vlln.tasks.env`).
* **Info**: ``episode_id``, ``house``; on the last step ``record``, the episode record as
  JSON (the same line ``vlln eval`` writes; score it with :mod:`vlln.tasks.metrics`).
* **Arguments** of ``gymnasium.make``: ``split`` (train/val/test, default test), ``houses``
  and ``preset`` (the benchmark's ``mp3d`` houses, as ``vlln eval`` scores on, or ``small``),
  or ``episode_file``; ``oracle`` ("rule", default, or an
  :class:`vlln.tasks.oracle_protocol.Oracle`); ``oracle_seed``; ``dialog_budget`` (IIGN,
  default 5); ``max_steps`` (500); ``privileged``; ``width``/``height`` of the camera
  (640×480); ``cache_dir`` of built splits.
* **Reset options**: ``episode_index`` (default: drawn with the reset's seed), and ``split``,
  ``houses``, ``preset``, ``episode_file`` or ``oracle`` to switch the episode source or the
  oracle.
* **Render**: ``render_mode="rgb_array"`` returns the first-person RGB frame.
* **Processes**: an environment made in a process forked after OpenGL was used there (an
  ``AsyncVectorEnv`` worker forked after an environment had stepped) runs in a fresh
  interpreter of its own (:mod:`vlln.gym.remote`), so ``make_vec(..., "async")`` works with the
  default start method; with ``context="spawn"`` the workers render themselves.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

from vlln.errors import ConfigError
from vlln.gym.remote import RemoteEnv
from vlln.gym.spaces import action_space, from_space, observation_space, to_space
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.camera import CameraSpec
from vlln.sim.gl_context import forked_after_gl
from vlln.sim.simulator import SimulatorConfig
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.oracle_protocol import Oracle
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskConfig, TaskType
from vlln.tasks.split_files import default_cache_dir, load_or_build_split
from vlln.tasks.splits import SPLIT_SIZES
from vlln.world.generator.presets import DEFAULT_PRESET
from vlln.world.generator.presets import preset as preset_of

_SOURCE_OPTIONS = ("split", "houses", "preset", "episode_file", "oracle")


class VllnEnv(gymnasium.Env[dict[str, Any], dict[str, Any]]):
    """One of the three tasks on the built-in houses or an episode file (module datasheet)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}  # noqa: RUF012

    def __init__(
        self,
        task: str = "iign",
        split: str = "test",
        houses: int | None = None,
        episode_file: str | None = None,
        oracle: str | Oracle = "rule",
        preset: str = DEFAULT_PRESET,
        oracle_seed: int = 0,
        dialog_budget: int | None = None,
        max_steps: int = DEFAULT_MAX_STEPS,
        privileged: bool = False,
        width: int = 640,
        height: int = 480,
        cache_dir: str | None = None,
        render_mode: str | None = None,
    ) -> None:
        self._remote: RemoteEnv | None = None
        if forked_after_gl():  # this process cannot render: play in a fresh one
            self._remote = RemoteEnv(
                {
                    "task": task,
                    "split": split,
                    "houses": houses,
                    "episode_file": episode_file,
                    "oracle": oracle,
                    "preset": preset,
                    "oracle_seed": oracle_seed,
                    "dialog_budget": dialog_budget,
                    "max_steps": max_steps,
                    "privileged": privileged,
                    "width": width,
                    "height": height,
                    "cache_dir": cache_dir,
                    "render_mode": render_mode,
                }
            )
        kind = TaskType.parse(task)
        if render_mode not in (None, "rgb_array"):
            raise ConfigError(f"render_mode {render_mode!r} is not supported; use 'rgb_array'")
        self.render_mode = render_mode
        self.config = TaskConfig(
            task=kind,
            max_steps=max_steps,
            dialog_budget=kind.default_budget if dialog_budget is None else dialog_budget,
        )
        self.privileged = privileged
        self._cache_dir = Path(cache_dir) if cache_dir else default_cache_dir()
        self._source = {
            "split": split,
            "houses": houses,
            "preset": preset_of(preset).name,
            "episode_file": episode_file,
        }
        self._oracle_seed = oracle_seed
        self._oracle_choice: str | Oracle = oracle
        sim_config = SimulatorConfig(camera=CameraSpec(width=width, height=height))
        self._scenes = SceneCache(sim_config)
        self._env: NavigationEnv | None = None
        self.observation_space = observation_space(
            sim_config.camera,
            sim_config.motion,
            self.config.dialog_budget if self.config.dialog_enabled else 0,
            privileged,
        )
        self.action_space = action_space()
        self._rgb: np.ndarray | None = None

    # ----------------------------------------------------------------- episode source
    @property
    def preset(self) -> str:
        """The preset of the built-in houses the episodes come from."""
        return str(self._source["preset"])

    def _episodes(self) -> list[Episode]:
        source = self._source
        if source["episode_file"]:
            return read_episodes(str(source["episode_file"]))
        split = str(source["split"])
        if split not in SPLIT_SIZES:
            raise ConfigError(f"unknown split {split!r}; choose one of: {', '.join(SPLIT_SIZES)}")
        houses = source["houses"] or SPLIT_SIZES[split]
        return load_or_build_split(
            split,
            self.config.task,
            int(houses),
            self._cache_dir,
            progress=False,
            preset=preset_of(str(source["preset"])).name,
        )

    def _oracle(self) -> Oracle | None:
        if not self.config.dialog_enabled:
            return None
        choice = self._oracle_choice
        if choice == "rule":
            return RuleOracle(self._oracle_seed)
        if isinstance(choice, str):
            raise ConfigError(f"unknown oracle {choice!r}; pass 'rule' or an Oracle object")
        return choice

    def _build(self) -> NavigationEnv:
        return NavigationEnv(
            self._episodes(), self.config, self._scenes, self._oracle(), self.privileged
        )

    # ----------------------------------------------------------------- Gymnasium API
    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[dict[str, Any], dict[str, Any]]:
        super().reset(seed=seed)
        if self._remote is not None:
            observation, info = self._remote.call("reset", seed=seed, options=options)
            self._rgb = observation["rgb"]
            return observation, info
        options = dict(options or {})
        changed = [key for key in _SOURCE_OPTIONS if key in options]
        for key in changed:
            value = options.pop(key)
            if key == "oracle":
                self._oracle_choice = value
            else:
                self._source[key] = value
        if key_error := set(options) - {"episode_index"}:
            raise ConfigError(
                f"unknown reset options {sorted(key_error)}; use episode_index, "
                + ", ".join(_SOURCE_OPTIONS)
            )
        if self._env is None or changed:
            self._env = self._build()
        if "episode_index" not in options:
            options["episode_index"] = int(self.np_random.integers(len(self._env.episodes)))
        observation, info = self._env.reset(options=options)
        self._rgb = observation["rgb"]
        return to_space(observation, self.privileged), info

    def step(self, action: Any) -> tuple[dict[str, Any], float, bool, bool, dict[str, Any]]:
        if self._remote is not None:
            stepped = self._remote.call("step", action)
            self._rgb = stepped[0]["rgb"]
            return stepped
        if self._env is None:
            raise ConfigError("call reset() before step()")
        observation, reward, terminated, truncated, info = self._env.step(from_space(action))
        self._rgb = observation["rgb"]
        if terminated or truncated:
            info["record"] = self._env.record("gymnasium").to_json()
        return to_space(observation, self.privileged), float(reward), terminated, truncated, info

    def render(self) -> np.ndarray | None:
        return self._rgb if self.render_mode == "rgb_array" else None

    def close(self) -> None:
        if self._remote is not None:
            self._remote.close()
        self._scenes.close()
        self._env = None
