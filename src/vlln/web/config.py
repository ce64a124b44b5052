"""Settings of the web app, checked once when it is built."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path

from vlln.agents.options import AgentOptions
from vlln.agents.registry import AGENTS, CONFIGURED_AGENTS, agent_options
from vlln.errors import ConfigError
from vlln.oracle.llm.openai_client import OpenAISettings
from vlln.tasks.episode import Episode
from vlln.tasks.spec import MAX_DIALOG_BUDGET, TaskType

PARTICIPANT_PATTERN = re.compile(r"^[A-Za-z0-9_.-]{1,32}$")
HUMAN_PREFIX = "human"


class OracleKind(StrEnum):
    """Who answers the navigator's questions."""

    RULES = "rules"  # the offline rule oracle
    LLM = "llm"  # a language model over an OpenAI-compatible server
    HUMAN = "human"  # a person on the oracle page


@dataclass(frozen=True)
class WebConfig:
    """What the web app serves and its limits.

    ``token``: when set, creating and listing sessions needs ``Authorization: Bearer <token>``
    (the lobby asks for it); the pages of a session need only its code. ``answer_time_limit_s``
    is how long a human oracle has for one answer (then the rule oracle answers, recorded as
    a fallback); ``idle_limit_s`` is how long a session may go without an action before it is
    recorded as abandoned. ``llm`` enables the language-model oracle.
    """

    episodes: tuple[Episode, ...]
    out: Path
    task: TaskType = TaskType.IIGN
    dialog_budget: int = 5
    max_steps: int = 500
    seed: int = 0
    token: str | None = None
    answer_time_limit_s: float = 90.0
    idle_limit_s: float = 1800.0
    max_live_sessions: int = 8
    max_body_bytes: int = 16 * 1024
    requests_per_second: float = 40.0
    request_burst: int = 80
    max_question_chars: int = 500
    max_answer_chars: int = 1000
    jpeg_quality: int = 85
    llm: OpenAISettings | None = None
    agent_options: Mapping[str, AgentOptions | Mapping[str, str]] = field(default_factory=dict)
    """Options of agents that take them, by agent; read into the agent's options class."""

    def __post_init__(self) -> None:
        if not self.episodes:
            raise ConfigError("the web app needs at least one episode to serve")
        if self.token is not None and (len(self.token) < 16 or self.token != self.token.strip()):
            raise ConfigError(
                "the token must be at least 16 characters without surrounding whitespace; "
                "make one with: python -c 'import secrets; print(secrets.token_urlsafe(24))'"
            )
        if not 0 <= self.dialog_budget <= MAX_DIALOG_BUDGET or (
            self.task != TaskType.IIGN and self.dialog_budget > 0
        ):
            raise ConfigError(
                f"dialog budget {self.dialog_budget} does not fit task {self.task.value}: "
                f"IIGN takes a budget of 0 to {MAX_DIALOG_BUDGET} (the paper's), the other tasks 0"
            )
        for name in ("answer_time_limit_s", "idle_limit_s", "requests_per_second"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ConfigError(f"{name} must be a positive number of seconds, got {value!r}")
        for name in (
            "max_steps",
            "max_live_sessions",
            "max_body_bytes",
            "request_burst",
            "max_question_chars",
            "max_answer_chars",
        ):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ConfigError(f"{name} must be a whole number >= 1, got {value!r}")
        if not 1 <= self.jpeg_quality <= 95:
            raise ConfigError(f"jpeg_quality must be in 1..95, got {self.jpeg_quality}")
        typed = {name: agent_options(name, given) for name, given in self.agent_options.items()}
        object.__setattr__(self, "agent_options", typed)

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
        kinds = [OracleKind.RULES, OracleKind.HUMAN]
        if self.llm is not None:
            kinds.insert(1, OracleKind.LLM)
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
