"""What the frontier agent perceives objects through: a detector, chosen by name."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from vlln.agents.frontier.perception.base import Detector, GroundTruthDetector
from vlln.agents.frontier.perception.noisy import NoiseModel, NoisyDetector
from vlln.errors import ConfigError
from vlln.tasks.env import DetectedObject

DETECTORS: tuple[str, ...] = ("truth", "noisy")
"""``truth``: the privileged ground-truth detector; ``noisy``: :class:`NoisyDetector`."""


def check_detector(name: str) -> str:
    """``name`` when it is a detector, else a one-line error naming the detectors."""
    if name not in DETECTORS:
        raise ConfigError(f"unknown detector {name!r}; choose one of: {', '.join(DETECTORS)}")
    return name


def make_detector(name: str, truth: Mapping[int, DetectedObject], seed: Sequence[int]) -> Detector:
    """The named detector over the ground-truth lookup ``truth``, seeded with ``seed``."""
    if check_detector(name) == "noisy":
        return NoisyDetector(truth, seed)
    return GroundTruthDetector(truth)


__all__ = [
    "DETECTORS",
    "Detector",
    "GroundTruthDetector",
    "NoiseModel",
    "NoisyDetector",
    "check_detector",
    "make_detector",
]
