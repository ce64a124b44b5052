"""The settings of a training-data export; recorded in ``export.json``."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

from vlln.errors import ConfigError


@dataclass(frozen=True)
class SftConfig:
    """How trajectories are cut into decisions and rendered into conversations.

    ``budget`` caps the oracle answers per trajectory (None = no cap): later questions are
    answered with the benchmark's refusal, as an agent over budget would be at evaluation.
    """

    budget: int | None = None
    history_frames: int = 8  # past frames sampled uniformly (dialog frames come on top)
    max_turn_run: int = 6  # turns in one output; 6 x 30° = 180°
    max_goal_steps: int = 8  # follower steps a pixel goal may stand for
    depth_tolerance: float = 0.1  # metres between rendered and projected depth of a goal
    image_size: int = 384  # side of the square history and current images
    jpeg_quality: int = 90

    def __post_init__(self) -> None:
        if self.budget is not None:
            _check_whole("budget", self.budget, 0)
        _check_whole("history_frames", self.history_frames, 0)
        _check_whole("max_turn_run", self.max_turn_run, 1)
        _check_whole("max_goal_steps", self.max_goal_steps, 1)
        _check_whole("image_size", self.image_size, 16)
        _check_whole("jpeg_quality", self.jpeg_quality, 1)
        if self.jpeg_quality > 95:
            raise ConfigError(f"jpeg_quality must be in [1, 95], got {self.jpeg_quality}")
        if not 0.0 < self.depth_tolerance <= 1.0:
            raise ConfigError(
                f"depth_tolerance must be in (0, 1] metres, got {self.depth_tolerance}"
            )

    def settings(self) -> dict[str, Any]:
        return asdict(self)


def _check_whole(name: str, value: object, low: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise ConfigError(f"{name} must be a whole number >= {low}, got {value!r}")
