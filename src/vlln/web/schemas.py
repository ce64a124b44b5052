"""Request bodies of the web API; every string has a length bound."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from vlln.sim.agent import Action

ACTIONS: dict[str, Action] = {
    "forward": Action.MOVE_FORWARD,
    "left": Action.TURN_LEFT,
    "right": Action.TURN_RIGHT,
    "up": Action.LOOK_UP,
    "down": Action.LOOK_DOWN,
    "stop": Action.STOP,
}


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class CreateSession(_Strict):
    navigator: str = Field(min_length=1, max_length=40)  # "human" or an agent name
    participant: str | None = Field(default=None, max_length=40)
    oracle: Literal["rules", "helpful", "llm", "human"] = "rules"
    episode_index: int | None = Field(default=None, ge=0)


class Join(_Strict):
    code: str = Field(min_length=1, max_length=64)


class Act(_Strict):
    action: Literal["forward", "left", "right", "up", "down", "stop"]


class Ask(_Strict):
    question: str = Field(min_length=1, max_length=4000)


class Answer(_Strict):
    number: int = Field(ge=1)
    answer: str = Field(min_length=1, max_length=4000)
