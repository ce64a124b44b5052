"""Settings of the web app, checked once when it is built."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Self

from pydantic import (
    AfterValidator,
    AliasChoices,
    Field,
    SkipValidation,
    field_validator,
    model_validator,
)

from vlln.agents.options import AgentOptions
from vlln.agents.registry import AGENTS, CONFIGURED_AGENTS, agent_options
from vlln.config import Config, Count
from vlln.errors import ConfigError
from vlln.oracle.llm.openai_client import OpenAISettings
from vlln.tasks.episode import Episode
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskType

PARTICIPANT_PATTERN = re.compile(r"^[A-Za-z0-9_.-]{1,32}$")
HUMAN_PREFIX = "human"
DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8770
DEFAULT_TOKEN_ENV = "VLLN_WEB_TOKEN"


class OracleKind(StrEnum):
    """Who answers the navigator's questions."""

    RULES = "rules"  # the offline rule oracle
    LLM = "llm"  # a language model over an OpenAI-compatible server
    HELPFUL = "helpful"  # the rule oracle and grounded help beyond the paper's questions
    HUMAN = "human"  # a person on the oracle page


def _seconds(value: float) -> float:
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"must be a positive number of seconds, got {value!r}")
    return value


Seconds = Annotated[float, AfterValidator(_seconds)]


class WebLimits(Config):
    """How sessions are played and the app's limits (``vlln serve web`` takes them as flags)."""

    task: TaskType = TaskType.IIGN
    """task of the served episodes"""
    max_steps: Count = DEFAULT_MAX_STEPS
    """counted-step cap of an episode"""
    seed: int = 0
    """seed of oracles and agents"""
    answer_time_limit_s: Annotated[
        Seconds, Field(validation_alias=AliasChoices("answer_time_limit", "answer_time_limit_s"))
    ] = 90.0
    """seconds a person has to answer (then the rule oracle answers, recorded as a fallback)"""
    idle_limit_s: Annotated[
        Seconds, Field(validation_alias=AliasChoices("idle_limit", "idle_limit_s"))
    ] = 1800.0
    """seconds without an action before a session is recorded as abandoned"""
    max_live_sessions: Annotated[
        Count, Field(validation_alias=AliasChoices("max_sessions", "max_live_sessions"))
    ] = 8
    """sessions played at once"""
    max_body_bytes: Count = 16 * 1024
    """largest request body accepted"""
    requests_per_second: Seconds = 40.0
    """requests a client may send per second, on average"""
    request_burst: Count = 80
    """requests a client may send at once"""
    max_question_chars: Count = 500
    """longest question a person may type"""
    max_answer_chars: Count = 1000
    """longest answer a person may type"""
    jpeg_quality: Annotated[int, Field(ge=1, le=95)] = 85
    """JPEG quality of the frames sent to the browser"""


class WebConfig(WebLimits):
    """What the web app serves and its limits.

    ``token``: when set, creating and listing sessions needs ``Authorization: Bearer <token>``
    (the lobby asks for it); the pages of a session need only its code. ``llm`` enables the
    language-model oracle; ``agent_options`` offers the agents that take options.
    """

    episodes: SkipValidation[tuple[Episode, ...]]
    out: Path
    dialog_budget: int = TaskType.IIGN.default_budget
    token: str | None = None
    llm: SkipValidation[OpenAISettings | None] = None
    agent_options: SkipValidation[Mapping[str, AgentOptions | Mapping[str, str]]] = Field(
        default_factory=dict
    )
    """Options of agents that take them, by agent; read into the agent's options class."""

    @field_validator("episodes")
    @classmethod
    def _some_episodes(cls, value: tuple[Episode, ...]) -> tuple[Episode, ...]:
        if not value:
            raise ValueError("the web app needs at least one episode to serve")
        return value

    @field_validator("token")
    @classmethod
    def _long_token(cls, value: str | None) -> str | None:
        if value is not None and (len(value) < 16 or value != value.strip()):
            raise ValueError(
                "the token must be at least 16 characters without surrounding whitespace; "
                "make one with: python -c 'import secrets; print(secrets.token_urlsafe(24))'"
            )
        return value

    @model_validator(mode="after")
    def _budget_fits_task(self) -> Self:
        self.task.check_budget(self.dialog_budget)
        return self

    @field_validator("agent_options")
    @classmethod
    def _typed_agent_options(
        cls, value: Mapping[str, AgentOptions | Mapping[str, str]]
    ) -> dict[str, AgentOptions]:
        return {name: agent_options(name, given) for name, given in value.items()}

    @property
    def agents(self) -> tuple[str, ...]:
        """The agents a session may choose: the plain ones, and those that take options
        (which server, which model) when the server was given them."""
        configured = [name for name in CONFIGURED_AGENTS if name in self.agent_options]
        return tuple(sorted([*AGENTS, *configured]))

    @property
    def oracles(self) -> tuple[OracleKind, ...]:
        """The oracles a session may choose here."""
        if self.dialog_budget == 0:
            return (OracleKind.RULES,)
        kinds = [OracleKind.RULES, OracleKind.HELPFUL, OracleKind.HUMAN]
        if self.llm is not None:
            kinds.insert(2, OracleKind.LLM)
        return tuple(kinds)


def check_participant(name: str) -> str:
    """A participant label as records show it: letters, digits, ``_ . -``, 1 to 32 of them."""
    if not PARTICIPANT_PATTERN.match(name):
        raise ConfigError(
            f"participant {name[:40]!r} is not a valid label; use 1 to 32 letters, digits, "
            "'_', '.' or '-'"
        )
    return name


def navigator_label(navigator: str, oracle: OracleKind) -> str:
    """The ``agent`` field of a record: the navigator, and the oracle unless it is the rule
    oracle that ``vlln eval`` runs use, so that pairings never share a record key."""
    if oracle == OracleKind.RULES:
        return navigator
    return f"{navigator} with {oracle.value} oracle"
