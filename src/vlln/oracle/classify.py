"""Offline question classification: what kind of question a navigator asked, and about what.

The paper's oracle asks a language model to sort each question into Attribute, Route,
Disambiguation or Other. Navigator questions come from a small space of intents, so weighted
phrase patterns do the same job deterministically, in microseconds and without a network.

Text is first normalised (:mod:`vlln.oracle.normalisation`: case, contractions, chat
spellings, typos, wrappers, embedded questions, word order), so the cues
(:mod:`vlln.oracle.question_cues` for disambiguation questions, :mod:`vlln.oracle.route_cues`,
:mod:`vlln.oracle.attribute_cues` and :mod:`vlln.oracle.other_cues` for the rest) see clean
lower-case words. Every cue that matches adds its weight to its topic and to the topic's
question type; the highest total wins, ties going to the more specific type. A question that
matches nothing is Other.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from enum import StrEnum
from functools import lru_cache
from typing import TypeVar

from vlln.oracle.attribute_cues import ATTRIBUTE_RULES
from vlln.oracle.normalisation import MATERIAL_SYNONYMS, ROOM_SYNONYMS, normalise, rephrase
from vlln.oracle.other_cues import OTHER_RULES
from vlln.oracle.question_cues import (
    DISAMBIGUATION_RULES,
    AttributeTopic,
    OtherTopic,
    RouteKind,
    Topic,
)
from vlln.oracle.route_cues import ROUTE_RULES
from vlln.tasks.oracle_protocol import QuestionType
from vlln.world.materials import COLORS

__all__ = [
    "AttributeTopic",
    "OtherTopic",
    "QuestionAnalysis",
    "RouteKind",
    "StepChoice",
    "analyse_question",
    "classify_question",
]


class StepChoice(StrEnum):
    """The action a step question proposes ("should I turn left?")."""

    LEFT = "left"
    RIGHT = "right"
    FORWARD = "forward"
    STOP = "stop"


@dataclass(frozen=True)
class QuestionAnalysis:
    """Everything the answerers need to know about a question's wording."""

    text: str  # the normalised text
    question_type: QuestionType
    route_kind: RouteKind | None = None
    attribute: AttributeTopic | None = None
    other: OtherTopic | None = None
    yes_no: bool = False  # "is it red?" rather than "what colour is it?"
    colors: tuple[str, ...] = ()  # colour words mentioned, longest first
    materials: tuple[str, ...] = ()  # material names mentioned
    rooms: tuple[str, ...] = ()  # room types mentioned
    this_room: bool = False  # "this room", "the room I am in"
    step_choice: StepChoice | None = None


def _type_of(topic: Topic) -> QuestionType:
    if isinstance(topic, QuestionType):
        return topic
    if isinstance(topic, RouteKind):
        return QuestionType.ROUTE
    return QuestionType.ATTRIBUTE if isinstance(topic, AttributeTopic) else QuestionType.OTHER


_RULES = (*DISAMBIGUATION_RULES, *ROUTE_RULES, *ATTRIBUTE_RULES, *OTHER_RULES)
# Text holds one sentence a line: "^" and "$" match at each sentence, ".*" stays inside one.
_COMPILED = [
    (re.compile(pattern, re.MULTILINE), weight, topic) for weight, topic, pattern in _RULES
]
# A tie goes to the earlier type: the more specific intent.
_TYPE_ORDER = (
    QuestionType.DISAMBIGUATION,
    QuestionType.ROUTE,
    QuestionType.OTHER,
    QuestionType.ATTRIBUTE,
)
_O, _P, _S = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP


def classify_question(text: str) -> QuestionType:
    """The question type of ``text`` (Attribute, Route, Disambiguation or Other)."""
    return analyse_question(text).question_type


@lru_cache(maxsize=4096)
def analysed(text: str) -> QuestionAnalysis:
    """:func:`analyse_question`, remembered: agents repeat their phrasings, and an analysis
    (frozen) depends on the text alone."""
    return analyse_question(text)


def analyse_question(text: str) -> QuestionAnalysis:
    """Type, topic and mentioned values of a question, by weighted phrase patterns."""
    sentences = rephrase(normalise(text))
    normalised = sentences.replace("\n", " ")  # object names keep their "_" (no room in them)
    type_scores = dict.fromkeys(_TYPE_ORDER, 0.0)
    topic_scores: dict[Topic, float] = {}
    for pattern, weight, topic in _COMPILED:
        if pattern.search(sentences):
            type_scores[_type_of(topic)] += weight
            topic_scores[topic] = topic_scores.get(topic, 0.0) + weight
    best = max(_TYPE_ORDER, key=lambda t: (type_scores[t], -_TYPE_ORDER.index(t)))
    if type_scores[best] == 0.0:
        best = QuestionType.OTHER
    analysis = QuestionAnalysis(
        text=normalised.replace("_", " "),
        question_type=best,
        yes_no=bool(_YES_NO_START.search(sentences.rsplit("\n", 1)[-1])),  # the last sentence
        colors=_mentioned(normalised, list(COLORS)),
        materials=_canonical(_mentioned(normalised, list(MATERIAL_SYNONYMS)), MATERIAL_SYNONYMS),
        rooms=_canonical(_mentioned(normalised, list(ROOM_SYNONYMS)), ROOM_SYNONYMS),
        this_room=bool(_THIS_ROOM.search(normalised)),
    )
    if best == QuestionType.ROUTE:
        kind = _top([_O, _S, _P], topic_scores)  # ties: the most direct answer
        step = _step_choice(normalised) if kind == RouteKind.STEP else None
        return replace(analysis, route_kind=kind, step_choice=step)
    if best == QuestionType.ATTRIBUTE:
        return replace(analysis, attribute=_top(list(AttributeTopic), topic_scores))
    if best == QuestionType.OTHER:
        other = _top(list(OtherTopic), topic_scores)
        scored = topic_scores.get(other, 0.0) > 0.0
        return replace(analysis, other=other if scored else OtherTopic.UNKNOWN)
    return analysis


_YES_NO_START = re.compile(r"^(is|are|was|were|does|do|did|can|could|should|shall|am|has|have)\b")
_THIS_ROOM = re.compile(r"\b(this|same|current) room\b|\broom (i am|we are) in\b")
_TopicT = TypeVar("_TopicT", RouteKind, AttributeTopic, OtherTopic)


def _top(topics: list[_TopicT], scores: dict[Topic, float]) -> _TopicT:
    """The best-scored topic; a tie goes to the one listed first."""
    return max(topics, key=lambda k: (scores.get(k, 0.0), -topics.index(k)))


def _canonical(words: tuple[str, ...], synonyms: dict[str, str]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(synonyms[w] for w in words))


def _mentioned(text: str, words: list[str]) -> tuple[str, ...]:
    """The words (possibly several tokens long) that occur in ``text``, longest first, each
    occurrence claimed once ("light gray" is not also "gray")."""
    found: list[str] = []
    remaining = f" {text} "
    for word in sorted(words, key=len, reverse=True):
        needle = f" {word} "
        if needle in remaining:
            found.append(word)
            remaining = remaining.replace(needle, " | ")
    return tuple(found)


_SIDE_MOVE = re.compile(r"\b(turn|go|head|move|keep|bear|veer) (to the )?(left|right)\b")
_NOT_A_SIDE = re.compile(r"\bright (here|now|there|way|direction|track|one|place|room)\b")


def _step_choice(text: str) -> StepChoice | None:
    """The action a step question proposes, if it proposes exactly one."""
    if re.search(r"\b(or|either)\b", text):
        return None  # a choice between actions, not a proposal of one
    if re.search(r"\bstop\b", text):
        return StepChoice.STOP
    moves = {m.group(3) for m in _SIDE_MOVE.finditer(text)}
    if not moves:
        sides = _NOT_A_SIDE.sub(" ", text)
        moves = {side for side in ("left", "right") if re.search(rf"\b{side}\b", sides)}
    if len(moves) == 1:
        return StepChoice.LEFT if "left" in moves else StepChoice.RIGHT
    if not moves and re.search(r"\b(forward|straight|ahead|keep going|continue)\b", text):
        return StepChoice.FORWARD
    return None
