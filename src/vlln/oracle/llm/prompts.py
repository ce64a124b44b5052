"""The paper's NPC prompts (supplementary, "NPC prompts"), and reading the type a model names.

Prompt 1 classifies a question; prompts 2, 3 and 4 answer Attribute, Route and Other questions
from ground-truth information. They are quoted as the paper prints them (typographic quotes
made plain). One addition: when the rule oracle has answered the question, its answer goes in
as a "Reference Answer" with a closing line asking for a rephrasing, so that the model words
grounded facts instead of inventing them; the offline model simply returns that reference.
"""

from __future__ import annotations

import re

from vlln.oracle.llm.protocol import Message
from vlln.tasks.oracle_protocol import QuestionType

QUESTION_MARKER = "QUESTION: "
REFERENCE_MARKER = "Reference Answer: "

CLASSIFICATION_PROMPT = (
    "You are a helpful assistant in classifying navigation task. You will be given a question "
    "among the following four types:\n"
    "1. Disambiguation: This question is asked to check whether the agent has found the goal "
    'object. Like "Is it the object you are looking for?"\n'
    "2. Route: This question is asked to get how to reach the target from the agent's current "
    'pose. Like "Which direction is the target?", "Where should I go now?", "Should I turn left '
    'or right here?"\n'
    "3. Attribute: This question is asked to get more information about the goal object. Like "
    '"Where is the goal object?", "What is the color of the goal object?"\n'
    "4. Other: If the question does not fall into any of the three types above.\n"
    "\n"
    "You need to classify the question into one of the four types. Only output the name of the "
    "type(disambiguation, route, attribute, other). Don't be verbose.\n"
    "\n"
    "Here is the question you need to classify\n"
    f"{QUESTION_MARKER}{{question}}"
)

_ANSWER_PREAMBLE = (
    "You are a helpful assistant in answering the question. Here follows the ground truth "
    "information you know. You need to answer the question based on the ground truth "
    "information.\n"
    "\n"
)
_QUESTION_TAIL = f"\n\nHere is the question you need to answer\n{QUESTION_MARKER}{{question}}"
_REPHRASE = (
    "\n\nRephrase the reference answer as a reply to the question. Keep every fact in it and "
    "add none. Don't be verbose."
)

ATTRIBUTE_PROMPT = (
    f"{_ANSWER_PREAMBLE}"
    "Here is the ground truth information about the goal object\n"
    "Goal Information: {goal_information}"
)
ROUTE_PROMPT = (
    f"{_ANSWER_PREAMBLE}"
    "Here is the ground truth information about next move\n"
    "Heading to Target: {heading}\n"
    "Correct Path: {path_description}\n"
    "Next Step: {next_step}"
)
OTHER_PROMPT = (
    f"{_ANSWER_PREAMBLE}"
    "Here is the ground truth information about the goal object, next move and task state\n"
    "Goal Information: {goal_information}\n"
    "Heading to Target: {heading}\n"
    "Correct Path: {path_description}\n"
    "Next Step: {next_step}\n"
    "Target Detected: {target_detected}"
)
# Not the paper's: help beyond its schema (docs/helpful-oracle.md), grounded by the helpful
# oracle, whose answer is always the reference to reword.
HELP_PROMPT = (
    f"{_ANSWER_PREAMBLE}"
    "Beyond where the goal object is and how to reach it, the asker may ask which of the "
    "objects in view is the goal, how sure you are, whether they passed it or are getting "
    "closer, which floor it is on, how many there are, and what is around it. The reference "
    "answer holds that help, grounded in the house, the asker's view and the path they "
    "walked\n"
    "Goal Information: {goal_information}\n"
    "Target Detected: {target_detected}\n"
    "Help Asked: {help_kind}"
)


def classification_messages(question: str) -> list[Message]:
    """Prompt 1 for ``question``, as one user message."""
    return [Message("user", CLASSIFICATION_PROMPT.replace("{question}", _one_line(question)))]


def answer_messages(
    facts_prompt: str, facts: dict[str, str], question: str, reference: str | None
) -> list[Message]:
    """Prompt 2, 3 or 4 (``facts_prompt``) filled with ``facts``, plus the reference answer
    and the request to rephrase it when there is one."""
    text = facts_prompt.format(**{key: _one_line(value) for key, value in facts.items()})
    if reference is not None:
        text += f"\n{REFERENCE_MARKER}{_one_line(reference)}"
    text += _QUESTION_TAIL.replace("{question}", _one_line(question))
    if reference is not None:
        text += _REPHRASE
    return [Message("user", text)]


def is_classification(prompt: str) -> bool:
    return prompt.startswith(CLASSIFICATION_PROMPT.split("\n", 1)[0])


def field_value(prompt: str, marker: str) -> str | None:
    """The rest of the line that starts with ``marker``, or None when no line does."""
    for line in prompt.splitlines():
        if line.startswith(marker):
            return line[len(marker) :]
    return None


_THINKING = re.compile(r"<think>.*?</think>", re.DOTALL | re.IGNORECASE)
_TYPE_WORDS = re.compile(r"\b(disambiguation|route|attribute|other)\b")
_NUMBERED = {"1": QuestionType.DISAMBIGUATION, "2": QuestionType.ROUTE}
_NUMBERED |= {"3": QuestionType.ATTRIBUTE, "4": QuestionType.OTHER}


def strip_thinking(reply: str) -> str:
    """The reply without a reasoning model's ``<think>...</think>`` blocks, trimmed."""
    return _THINKING.sub(" ", reply).strip()


def parse_question_type(reply: str) -> QuestionType | None:
    """The type a classification reply names, or None when it names none or several.

    Accepts the bare name in any case, with punctuation, markdown or a reasoning model's
    ``<think>`` block around it ("**Route**", "Type: route."), and the prompt's list number.
    """
    text = strip_thinking(reply).lower()
    names = set(_TYPE_WORDS.findall(text))
    if len(names) == 1:
        return QuestionType(names.pop())
    if not names:
        bare = re.sub(r"[^a-z0-9]", "", text)
        return _NUMBERED.get(bare)
    return None


def _one_line(text: str) -> str:
    """Facts and questions stay on their line, so markers cannot be forged by their content."""
    return " ".join(text.split())
