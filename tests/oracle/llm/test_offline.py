"""The offline model: the offline classifier's type and the reference answer, nothing else."""

from __future__ import annotations

import pytest

from vlln.oracle.classify import classify_question
from vlln.oracle.llm.offline import OfflineLanguageModel
from vlln.oracle.llm.prompts import ATTRIBUTE_PROMPT, answer_messages, classification_messages
from vlln.oracle.llm.protocol import LanguageModel, LanguageModelReplyError, Message


@pytest.mark.parametrize(
    "question", ["What color is it?", "Which way should I go?", "Is this the one?", "Hi there"]
)
def test_classification_is_the_offline_classifiers(question: str) -> None:
    model: LanguageModel = OfflineLanguageModel()
    result = model.complete(classification_messages(question), max_tokens=8, temperature=0.0)
    assert result.text == classify_question(question).value
    assert result.backend == "offline" and result.usage.total_tokens == 0 and not result.cached


def test_answers_return_the_reference_and_free_prompts_are_refused() -> None:
    model = OfflineLanguageModel()
    facts = {"goal_information": "category: chair; color: red"}
    messages = answer_messages(ATTRIBUTE_PROMPT, facts, "What color?", "It is red.")
    assert model.complete(messages, max_tokens=8, temperature=0.0).text == "It is red."
    for free in (
        answer_messages(ATTRIBUTE_PROMPT, facts, "What color?", None),
        [Message("user", "Tell me a joke.")],
    ):
        with pytest.raises(LanguageModelReplyError, match="offline model"):
            model.complete(free, max_tokens=8, temperature=0.0)
