"""The settings of a training-data export; recorded in ``export.json``."""

from __future__ import annotations

from typing import Annotated, Self

from pydantic import AliasChoices, Field, model_validator

from vlln.config import Config
from vlln.prompt import DEFAULT_HISTORY_COUNT, MAX_TURN_RUN


class SftConfig(Config):
    """How trajectories are sampled into conversations; the defaults are the reference's.

    One sample every ``sample_step`` frames; every STOP frame and every frame where questions
    were asked is repeated ``repeats`` times; each sample draws how many answers the model
    still gets (``min_answers`` to ``max_answers``), later ones reading the question-limit
    answer.
    """

    seed: Annotated[int, Field(ge=0)] = 0
    """seed of every random choice"""
    sample_step: Annotated[int, Field(ge=1)] = 4
    """one sample every N frames"""
    repeats: Annotated[int, Field(ge=1)] = 10
    """copies of each STOP frame and of each frame where questions were asked"""
    min_answers: Annotated[int, Field(ge=0)] = 0
    """fewest answers a sample's model may still get (each sample draws this to max-answers)"""
    max_answers: Annotated[int, Field(ge=0)] = 6
    """most answers a sample's model may still get (each sample draws min-answers to N)"""

    @model_validator(mode="after")
    def _answers_range(self) -> Self:
        if self.min_answers > self.max_answers:
            raise ValueError(
                f"--min-answers {self.min_answers} is above --max-answers {self.max_answers}"
            )
        return self

    history_frames: Annotated[
        int, Field(ge=1, validation_alias=AliasChoices("history", "history_frames"))
    ] = DEFAULT_HISTORY_COUNT
    """history frames in each prompt"""
    max_turn_run: Annotated[int, Field(ge=1, le=MAX_TURN_RUN)] = MAX_TURN_RUN
    """longest run of turns one answer names"""
    forward_steps: bool = False
    """a one-step <move>↑ sample at each forward frame with no visible pixel goal (the
    reference writes none there, so an imitator has no decision to copy at the steps too close
    to show on the look-down image, the last before most STOPs among them)"""
    unrecorded_at_default = ("hard_negatives",)  # exports made before it stay byte for byte

    hard_negatives: Annotated[int, Field(ge=0)] = 0
    """copies of a sample at each frame where another instance of the target's category is in
    plain view and the teacher walked on (IIGN, IGN; 0: none): a model that weakly matches the
    target's attributes stops at such a distractor (the paper's AD failure)"""
