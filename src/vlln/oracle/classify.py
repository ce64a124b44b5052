"""Offline question classification: what kind of question a navigator asked, and about what.

The paper's oracle asks a language model to sort each question into Attribute, Route,
Disambiguation or Other. Here a small learned model does it offline, in well under a
millisecond: TF-IDF over word and character n-grams with a linear classifier
(:mod:`vlln.oracle.classifier`), trained on the packaged labelled questions. It predicts one
label that gives both the type and the topic the answerer needs (``attribute:color``,
``route:step``, ``other:distance``, ``disambiguation``); character n-grams make it robust to
typos and chat spellings. The values a question names (colours, materials, rooms) are
look-ups of the house vocabularies (:mod:`vlln.oracle.classifier.entities`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

from vlln.oracle.classifier.entities import (
    MATERIAL_SYNONYMS,
    ROOM_SYNONYMS,
    THIS_ROOM,
    YES_NO_OPENERS,
    canonical,
    corrected_words,
    mentioned,
    step_choice,
)
from vlln.oracle.classifier.model import packaged_classifier, prepared
from vlln.oracle.topics import AttributeTopic, OtherTopic, RouteKind, StepChoice, parse_label
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


@dataclass(frozen=True)
class QuestionAnalysis:
    """Everything the answerers need to know about a question's wording."""

    text: str  # lower-case words, typos in vocabulary words corrected
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


def classify_question(text: str) -> QuestionType:
    """The question type of ``text`` (Attribute, Route, Disambiguation or Other)."""
    return analyse_question(text).question_type


@lru_cache(maxsize=4096)
def analysed(text: str) -> QuestionAnalysis:
    """:func:`analyse_question`, remembered: agents repeat their phrasings, and an analysis
    (frozen) depends on the text alone."""
    return analyse_question(text)


_SENTENCE_END = re.compile(r"[.?!;\n]+")


def analyse_question(text: str) -> QuestionAnalysis:
    """Type, topic and mentioned values of a question."""
    sentences = [prepared(s) for s in _SENTENCE_END.split(text)]
    sentences = [s for s in sentences if s]
    words = corrected_words(prepared(text).split())
    normalised = " ".join(words)
    if not words:
        return QuestionAnalysis(normalised, QuestionType.OTHER, other=OtherTopic.UNKNOWN)
    question_type, topic = parse_label(packaged_classifier().predict(text))
    last = sentences[-1].split()
    route = topic if isinstance(topic, RouteKind) else None
    return QuestionAnalysis(
        text=normalised,
        question_type=question_type,
        route_kind=route,
        attribute=topic if isinstance(topic, AttributeTopic) else None,
        other=topic if isinstance(topic, OtherTopic) else None,
        yes_no=bool(last) and last[0] in YES_NO_OPENERS,
        colors=mentioned(normalised, list(COLORS)),
        materials=canonical(mentioned(normalised, list(MATERIAL_SYNONYMS)), MATERIAL_SYNONYMS),
        rooms=canonical(mentioned(normalised, list(ROOM_SYNONYMS)), ROOM_SYNONYMS),
        this_room=any(f" {p} " in f" {normalised} " for p in THIS_ROOM),
        step_choice=step_choice(words) if route == RouteKind.STEP else None,
    )
