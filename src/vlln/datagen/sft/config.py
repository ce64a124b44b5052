"""The settings of a training-data export; recorded in ``export.json``."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

from vlln.errors import ConfigError
from vlln.prompt import DEFAULT_HISTORY_COUNT, MAX_TURN_RUN


@dataclass(frozen=True)
class SftConfig:
    """How trajectories are sampled into conversations; the defaults are the reference's.

    One sample every ``sample_step`` frames; every STOP frame and every frame where questions
    were asked is repeated ``repeats`` times; each sample draws how many answers the model
    still gets (0 to ``max_answers``), later ones reading the question-limit answer.
    """

    seed: int = 0
    sample_step: int = 4
    repeats: int = 10
    max_answers: int = 6
    history_frames: int = DEFAULT_HISTORY_COUNT
    max_turn_run: int = MAX_TURN_RUN

    def __post_init__(self) -> None:
        _check_whole("seed", self.seed, 0)
        _check_whole("sample_step", self.sample_step, 1)
        _check_whole("repeats", self.repeats, 1)
        _check_whole("max_answers", self.max_answers, 0)
        _check_whole("history_frames", self.history_frames, 1)
        _check_whole("max_turn_run", self.max_turn_run, 1)
        if self.max_turn_run > MAX_TURN_RUN:
            raise ConfigError(
                f"max_turn_run must be at most {MAX_TURN_RUN}, got {self.max_turn_run}"
            )

    def settings(self) -> dict[str, Any]:
        return asdict(self)


def _check_whole(name: str, value: object, low: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise ConfigError(f"{name} must be a whole number >= {low}, got {value!r}")
