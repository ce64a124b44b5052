"""The settings of a training-data export; recorded in ``export.json``."""

from __future__ import annotations

from typing import Annotated

from pydantic import AliasChoices, Field

from vlln.config import Config
from vlln.prompt import DEFAULT_HISTORY_COUNT, MAX_TURN_RUN


class SftConfig(Config):
    """How trajectories are sampled into conversations; the defaults are the reference's.

    One sample every ``sample_step`` frames; every STOP frame and every frame where questions
    were asked is repeated ``repeats`` times; each sample draws how many answers the model
    still gets (0 to ``max_answers``), later ones reading the question-limit answer.
    """

    seed: Annotated[int, Field(ge=0)] = 0
    """seed of every random choice"""
    sample_step: Annotated[int, Field(ge=1)] = 4
    """one sample every N frames"""
    repeats: Annotated[int, Field(ge=1)] = 10
    """copies of each STOP frame and of each frame where questions were asked"""
    max_answers: Annotated[int, Field(ge=0)] = 6
    """most answers a sample's model may still get (each sample draws 0 to N)"""
    history_frames: Annotated[
        int, Field(ge=1, validation_alias=AliasChoices("history", "history_frames"))
    ] = DEFAULT_HISTORY_COUNT
    """history frames in each prompt"""
    max_turn_run: Annotated[int, Field(ge=1, le=MAX_TURN_RUN)] = MAX_TURN_RUN
    """longest run of turns one answer names"""
