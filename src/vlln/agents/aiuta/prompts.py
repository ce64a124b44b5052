"""The prompts of the AIUTA-style agent and the reading of their replies.

AIUTA (Taioli et al., "Collaborative Instance Object Navigation: Leveraging
Uncertainty-Awareness to Minimize Human-Agent Dialogues", arXiv 2412.01250, 2024/2025) runs,
whenever its detector finds an object of the target category, a self-dialogue between a
vision-language model (VLM) and a language model (LLM):

1. **Self-Questioner**: the VLM describes the detected object; the LLM writes
   attribute-specific questions that check that description; the VLM answers each one, and
   answers it is unsure of are dropped; the LLM rewrites the description from what survives.
2. **Interaction Trigger**: the LLM compares that description with the facts known about the
   target (the instruction and the user's answers so far) and gives an alignment score; above
   a stop threshold the agent stops at the object, below a skip threshold it explores on, and
   in between it asks the user the question the LLM proposes.

The paper's exact prompt text was not available to us; these prompts follow its structure
and its stages, in our own words. AIUTA estimates the VLM's uncertainty from the normalized
entropy of its answer tokens, which needs token log-probabilities that not every
OpenAI-compatible server returns; we use the answer set of its IDKVQA data instead (an answer
may be "I don't know") and drop the answers that say so. One model serves as both the VLM
and the LLM.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

UNSURE = "I don't know"
_SCORE = re.compile(r"score\s*[:=]\s*(\d+(?:\.\d+)?)", re.IGNORECASE)
_QUESTION = re.compile(r"question\s*[:=]\s*(.+)", re.IGNORECASE)
_LEADER = re.compile(r"^\s*(?:[-*•]|\d+[.)])\s*")
_MAX_QUESTION_CHARS = 300


def describe(category: str) -> str:
    """Self-Questioner, VLM: the first description of the object in view."""
    return (
        f"You are a robot searching a house for a {category}. Describe the {category} in the "
        "middle of the image in one or two sentences: its colour, material, shape and size, "
        "and the objects next to it. Say only what you can see."
    )


def self_questions(category: str, description: str, count: int) -> str:
    """Self-Questioner, LLM: questions that check the description's details."""
    return (
        f"A robot searching for a {category} described what it sees:\n"
        f'"{description}"\n'
        f"Write at most {count} short questions, one per line, that check the details of this "
        f"description which tell this {category} apart from others of its kind (colour, "
        "material, shape, size, what is next to it). Write only the questions."
    )


def answer(category: str, question: str) -> str:
    """Self-Questioner, VLM: one self-question about the image."""
    return (
        f"Look at the {category} in the middle of the image. {question} Answer in a few words. "
        f"If the image does not let you tell, answer exactly: {UNSURE}."
    )


def refine(category: str, description: str, checks: Sequence[tuple[str, str]]) -> str:
    """Self-Questioner, LLM: the description rewritten from the checks that were sure."""
    lines = "\n".join(f"Q: {q}\nA: {a}" for q, a in checks) or "(none)"
    return (
        f'A robot described a {category}: "{description}"\n'
        f"It then checked the image:\n{lines}\n"
        f"Rewrite the description of the {category} in one or two sentences, keeping only "
        "what the checks confirm or do not contradict."
    )


def trigger(category: str, facts: Sequence[str], observation: str) -> str:
    """Interaction Trigger, LLM: the alignment score and the question to ask."""
    known = "\n".join(f"- {fact}" for fact in facts)
    return (
        f"You help a robot find one particular {category} in a house.\n"
        f"What is known about the target:\n{known}\n"
        f"What the robot sees now: {observation}\n"
        "Rate from 0 to 10 how likely the object seen is the target: 10 when everything known "
        "matches it, 0 when something known contradicts it. Then write the one question to "
        "the user whose answer would best settle the doubt.\n"
        "Reply in two lines:\nScore: <0-10>\nQuestion: <the question>"
    )


def read_questions(text: str, count: int) -> list[str]:
    """The self-questions of an LLM reply: its lines that end with a question mark."""
    found = []
    for line in text.splitlines():
        line = _LEADER.sub("", line).strip()
        if line.endswith("?") and line not in found:
            found.append(line[:_MAX_QUESTION_CHARS])
    return found[:count]


def is_unsure(reply: str) -> bool:
    """Whether a VLM answer says it cannot tell."""
    text = reply.lower().replace("’", "'")
    return "don't know" in text or "do not know" in text or "cannot tell" in text


@dataclass(frozen=True)
class Verdict:
    """The Interaction Trigger's reply: alignment score (0-10) and the proposed question."""

    score: float
    question: str | None


def read_verdict(text: str) -> Verdict | None:
    """The score and question of a trigger reply; None when it gives no score in 0-10."""
    score = _SCORE.search(text)
    if score is None or not 0.0 <= float(score.group(1)) <= 10.0:
        return None
    question = _QUESTION.search(text)
    asked = question.group(1).strip()[:_MAX_QUESTION_CHARS] if question else ""
    return Verdict(float(score.group(1)), asked or None)
