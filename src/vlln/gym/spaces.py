"""Gymnasium spaces for the navigation environment, and the conversions into and out of them.

Text (the instruction, the oracle's answer, the agent's question) uses :class:`spaces.Text`
over printable characters; numbers that are scalars in :mod:`vlln.tasks.env` (compass, tilt)
are arrays of shape (1,) here, as Gymnasium's ``Box`` wants.
"""

from __future__ import annotations

import math
import string
from typing import Any

import numpy as np
from gymnasium import spaces

from vlln.errors import ConfigError
from vlln.sim.agent import Action, MotionConfig
from vlln.sim.camera import CameraSpec
from vlln.tasks.spec import AgentOutput, Talk
from vlln.world.model import StructureId

TALK = len(Action)
"""The action index that asks a question (the indices below it are :class:`Action`)."""

MAX_GPS = 1000.0
"""Metres from the start the ``gps`` and ``height`` spaces admit (houses are tens of metres
across and a few storeys high)."""

MAX_TEXT = 1024
"""Characters of an instruction, answer or question the spaces admit."""

# Printable ASCII plus the Latin-1 letters and the typographic punctuation that descriptions use.
CHARSET = frozenset(string.printable + "".join(chr(c) for c in range(0xA0, 0x180)) + "‘’“”–—…°×")


def text_space(min_length: int = 0) -> spaces.Text:
    return spaces.Text(max_length=MAX_TEXT, min_length=min_length, charset=CHARSET)


def observation_space(
    camera: CameraSpec, motion: MotionConfig, budget: int, privileged: bool
) -> spaces.Dict:
    """Every key of :meth:`vlln.tasks.env.NavigationEnv.reset`'s observations."""
    h, w = camera.height, camera.width
    low_tilt, high_tilt = math.radians(motion.min_tilt_deg), math.radians(motion.max_tilt_deg)
    items: dict[str, spaces.Space[Any]] = {
        "rgb": spaces.Box(0, 255, (h, w, 3), np.uint8),
        "depth": spaces.Box(0.0, camera.max_depth, (h, w), np.float32),
        "gps": spaces.Box(-MAX_GPS, MAX_GPS, (2,), np.float32),
        "height": spaces.Box(-MAX_GPS, MAX_GPS, (1,), np.float32),
        "compass": spaces.Box(-math.pi, math.pi, (1,), np.float32),
        "tilt": spaces.Box(low_tilt - 1e-6, high_tilt + 1e-6, (1,), np.float32),
        "instruction": text_space(1),
        "oracle_answer": text_space(),
        "questions_left": spaces.Discrete(budget + 1),
    }
    if privileged:
        lowest = min(StructureId)  # the structure's ids are negative, objects' positive
        items["instance_ids"] = spaces.Box(int(lowest), np.iinfo(np.int32).max, (h, w), np.int32)
        items["expert_action"] = spaces.Discrete(len(Action))
    return spaces.Dict(items)


def action_space() -> spaces.Dict:
    """``action``: an :class:`Action` index, or :data:`TALK` to ask ``question``."""
    return spaces.Dict({"action": spaces.Discrete(len(Action) + 1), "question": text_space()})


def to_space(observation: dict[str, Any], privileged: bool) -> dict[str, Any]:
    """An environment observation in the types the observation space holds."""
    out: dict[str, Any] = {
        "rgb": observation["rgb"].copy(),  # a TALK step shows the same frame again
        "depth": observation["depth"].copy(),
        "gps": observation["gps"],
        "height": np.array([observation["height"]], np.float32),
        "compass": np.array([observation["compass"]], np.float32),
        "tilt": np.array([observation["tilt"]], np.float32),
        "instruction": observation["instruction"],
        "oracle_answer": observation["oracle_answer"] or "",
        "questions_left": int(observation["questions_left"]),
    }
    if privileged:
        out["instance_ids"] = observation["instance_ids"].astype(np.int32)
        expert = observation["expert_action"]
        out["expert_action"] = int(expert if expert is not None else Action.STOP)
    return out


def from_space(action: Any) -> AgentOutput:
    """A space action (a dict, or a bare index for the motion actions) as the environment's."""
    if isinstance(action, dict):
        index = int(action["action"])
        if index == TALK:
            return Talk(str(action.get("question", "")))
    else:
        index = int(action)
    if not 0 <= index < TALK:
        raise ConfigError(f"action index {index} is outside 0..{TALK} (TALK = {TALK})")
    return Action(index)
