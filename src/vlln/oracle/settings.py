"""Which oracle answers and what it may answer: the settings of the paper's oracle ablations.

* ``backend``: the rule oracle, the paper's language-model oracle over an
  OpenAI-compatible server (the oracle-backbone ablation, paper supplementary), or the
  helpful oracle, the rule oracle's answers and grounded help beyond them
  (docs/helpful-oracle.md), worded by a language model when ``llm`` is given.
* ``question_types``: the types answered; a question of another type gets
  :data:`vlln.oracle.rule_oracle.TYPE_REFUSAL` and still costs its turn (the question-type
  ablation).
* ``disambiguation``: ``plain`` answers "is this the one?" with yes or no only, as the
  paper's oracle does; ``cues`` adds how the target differs from the object in view.

The API key is never part of the settings: only the name of the variable that holds it.
"""

from __future__ import annotations

from enum import StrEnum
from functools import lru_cache
from typing import Self

import httpx
import numpy as np
from pydantic import model_validator

from vlln.config import settings_dataclass
from vlln.errors import ConfigError
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.llm.openai_client import (
    OpenAIChatClient,
    OpenAISettings,
    check_server_answers,
)
from vlln.oracle.llm_oracle import LLMOracle
from vlln.oracle.rule_oracle import ALL_QUESTION_TYPES, RuleOracle
from vlln.tasks.oracle_protocol import Oracle, QuestionType


class OracleBackend(StrEnum):
    """Who words the answers."""

    RULES = "rules"  # the offline rule oracle
    LLM = "llm"  # a language model over an OpenAI-compatible server
    HELPFUL = "helpful"  # the rule oracle and grounded help beyond the paper's questions


class Disambiguation(StrEnum):
    """How "is this the one?" is answered."""

    PLAIN = "plain"  # yes or no, the paper's oracle
    CUES = "cues"  # a "no" also says how the target differs ("No, the one I mean is red.")


def parse_question_types(text: str) -> tuple[QuestionType, ...]:
    """``"attribute,route"`` -> the types in their canonical order; unknown names refused."""
    names = [part.strip().lower() for part in text.split(",") if part.strip()]
    known = {kind.value: kind for kind in QuestionType}
    unknown = [name for name in names if name not in known]
    if unknown:
        raise ConfigError(
            f"unknown question type {unknown[0]!r}; choose from {', '.join(known)} "
            "(comma-separated, e.g. attribute,route)"
        )
    return tuple(kind for kind in QuestionType if kind.value in names)


@settings_dataclass
class OracleSettings:
    """The oracle of a run: its backend (``llm`` needs ``llm``, the server's settings), the
    question types it answers, and how it answers disambiguation questions."""

    backend: OracleBackend = OracleBackend.RULES
    llm: OpenAISettings | None = None
    question_types: tuple[QuestionType, ...] = ALL_QUESTION_TYPES
    disambiguation: Disambiguation = Disambiguation.PLAIN

    @model_validator(mode="after")
    def _llm_settings_for_a_model(self) -> Self:
        if self.backend == OracleBackend.LLM and self.llm is None:
            raise ConfigError("the llm oracle needs its server's settings (--oracle-model)")
        if self.backend == OracleBackend.RULES and self.llm is not None:
            raise ConfigError(
                "the rule oracle takes no server; pass --oracle llm or helpful with "
                "--oracle-model, or neither"
            )
        return self

    @property
    def oracle_name(self) -> str:
        """The class that answers, as run.json's provenance names it."""
        if self.llm is not None:
            return "LLMOracle"
        return "HelpfulOracle" if self.backend == OracleBackend.HELPFUL else "RuleOracle"

    @property
    def backend_name(self) -> str:
        """How records name the backend: ``rules``, ``helpful`` or ``openai:<model>@<host>``."""
        if self.llm is None:
            return self.backend.value
        return llm_backend_name(self.llm)

    def make(self, seed: int) -> Oracle:
        """A fresh oracle for one episode, seeded (paraphrases), over the client that every
        episode of the process shares (its pool, and its count of failed requests in a row)."""
        rules = RuleOracle(seed, question_types=self.question_types, cues=self.cues)
        helpful = self.backend == OracleBackend.HELPFUL
        if self.llm is not None:
            return LLMOracle(_shared_client(self.llm), seed, rules, helpful=helpful)
        return HelpfulOracle(rules) if helpful else rules

    def check_server(self) -> None:
        """:class:`ConfigError` unless the llm oracle's server answers (nothing for rules)."""
        if self.llm is not None:
            check_server_answers(self.llm, "--oracle-base-url")

    @property
    def cues(self) -> bool:
        return self.disambiguation == Disambiguation.CUES


@lru_cache(maxsize=8)
def _shared_client(settings: OpenAISettings) -> OpenAIChatClient:
    return OpenAIChatClient(settings, rng=np.random.default_rng(0))


def llm_backend_name(settings: OpenAISettings) -> str:
    """The backend name the client gives its replies, without making a client."""
    return f"openai:{settings.model}@{httpx.URL(settings.base_url).host}"
