"""The oracle service's wire format: pydantic models for every request and response.

Requests are strict on purpose, because the clients are programs in other languages and robots
whose mistakes should surface at once rather than be guessed around: unknown fields are
rejected, numbers must be finite JSON numbers (not strings, not ``NaN``), strings have length
limits, and positions must lie within :data:`MAX_COORDINATE` metres of the origin.
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from vlln.tasks.spec import MAX_DIALOG_BUDGET, TaskType

MAX_QUESTION_CHARS = 1000
MAX_ID_CHARS = 200
MAX_COORDINATE = 10_000.0  # metres; far beyond any house, small enough to stay exact
SESSION_ID_PATTERN = r"^[A-Za-z0-9_-]{1,64}$"

Coordinate = Annotated[float, Field(ge=-MAX_COORDINATE, le=MAX_COORDINATE)]
QuestionType = Literal["attribute", "route", "disambiguation", "other", "refused"]
OracleName = Literal["rules", "helpful"]


class _Request(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class _Response(BaseModel):
    model_config = ConfigDict(frozen=True)


class Pose(_Request):
    """Where the asker stands and looks, in the Habitat frame of :mod:`vlln.world.frame`:
    ``position`` (x, y, z) with y the height of the floor (or stair tread) under it, ``yaw``
    (0 looks along -z, positive = turned left) and ``tilt`` (camera pitch, positive looking
    up), both in radians."""

    position: list[Coordinate] = Field(min_length=3, max_length=3)
    yaw: float = Field(ge=-4.0 * math.pi, le=4.0 * math.pi)
    tilt: float = Field(default=0.0, ge=-math.pi / 2.0, le=math.pi / 2.0)


class CreateSessionRequest(_Request):
    """Either a scene and a target instance, or an episode of the server's episode file."""

    scene_id: str | None = Field(default=None, min_length=1, max_length=MAX_ID_CHARS)
    target_instance_id: int | None = Field(default=None, ge=1)
    episode_id: str | None = Field(default=None, min_length=1, max_length=MAX_ID_CHARS)
    dialog_budget: int = Field(
        default=TaskType.IIGN.default_budget, ge=0, le=MAX_DIALOG_BUDGET
    )  # the paper's range, as in the environment
    oracle: OracleName = "rules"  # the paper's rule oracle, or the helpful oracle

    @model_validator(mode="after")
    def _one_target(self) -> CreateSessionRequest:
        by_scene = self.scene_id is not None or self.target_instance_id is not None
        if self.episode_id is not None and by_scene:
            raise ValueError("give either episode_id or scene_id with target_instance_id, not both")
        if self.episode_id is None and (self.scene_id is None or self.target_instance_id is None):
            raise ValueError("give scene_id and target_instance_id, or episode_id")
        return self


class CreateSessionResponse(_Response):
    session_id: str
    scene_id: str
    episode_id: str | None
    target_category: str
    instruction: str | None
    dialog_budget: int
    questions_left: int


class AskRequest(_Request):
    question: str = Field(min_length=1, max_length=MAX_QUESTION_CHARS)
    pose: Pose


class AskResponse(_Response):
    answer: str
    question_type: QuestionType
    answered: bool
    questions_left: int
    help_kind: str | None = None  # the helpful oracle's kind of help (docs/helpful-oracle.md)


class DialogTurnView(_Response):
    question: str
    answer: str
    question_type: QuestionType
    answered: bool
    pose: Pose
    help_kind: str | None = None


class SessionView(_Response):
    session_id: str
    scene_id: str
    episode_id: str | None
    target_category: str
    dialog_budget: int
    questions_left: int
    refused_questions: int  # asked past the budget; the dialog keeps only the first few
    dialog: list[DialogTurnView]


class HealthResponse(_Response):
    status: Literal["ok"]
    version: str
    sessions: int
    max_sessions: int


class ErrorBody(_Response):
    """Every error response: a short ``error`` and a ``detail`` saying what to change."""

    error: str
    detail: str | dict[str, object] | list[dict[str, object]]
