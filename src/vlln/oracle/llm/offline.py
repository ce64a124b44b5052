"""The offline language model: what the rule-based oracle would say, with no network.

It reads the oracle's own prompts (:mod:`vlln.oracle.llm.prompts`): a classification prompt
gets the offline classifier's type, an answer prompt gets its reference answer back
unchanged. It is the reproducible default and the stand-in when a server fails, and it
spends no tokens.
"""

from __future__ import annotations

from vlln.oracle.classify import classify_question
from vlln.oracle.llm.prompts import (
    QUESTION_MARKER,
    REFERENCE_MARKER,
    field_value,
    is_classification,
)
from vlln.oracle.llm.protocol import Completion, LanguageModelReplyError, Message, Usage

OFFLINE_BACKEND = "offline"


class OfflineLanguageModel:
    """Deterministic completions for the oracle's prompts; same prompt, same text."""

    backend = OFFLINE_BACKEND

    def complete(
        self, messages: list[Message], *, max_tokens: int, temperature: float
    ) -> Completion:
        prompt = next((m.text for m in reversed(messages) if m.role == "user"), "")
        if is_classification(prompt):
            question = field_value(prompt, QUESTION_MARKER)
            if question is not None:
                return Completion(classify_question(question).value, Usage(), self.backend)
        reference = field_value(prompt, REFERENCE_MARKER)
        if reference is None:
            raise LanguageModelReplyError(
                "the offline model only answers the oracle's prompts: a classification prompt "
                f"or an answer prompt with a {REFERENCE_MARKER.strip()!r} line; use a server "
                "model for free-form prompts"
            )
        return Completion(reference, Usage(), self.backend)
