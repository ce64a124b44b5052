"""The topics of a navigator's questions, and the labels the question classifier predicts.

A label joins a question type and the topic its answerer needs: ``attribute:color``,
``route:step``, ``other:distance``; a disambiguation question has no topic, so its label is
just ``disambiguation``.
"""

from __future__ import annotations

from enum import StrEnum

from vlln.tasks.oracle_protocol import QuestionType


class RouteKind(StrEnum):
    """Granularity of a route question (paper §3.2): heading, path through rooms, next action."""

    ORIENTATION = "orientation"
    PATH = "path"
    STEP = "step"


class AttributeTopic(StrEnum):
    """Which fact about the target an attribute question asks for."""

    COLOR = "color"
    MATERIAL = "material"
    TEXTURE = "texture"
    SHAPE = "shape"
    SIZE = "size"
    ROOM = "room"
    LOCATION = "location"  # "where is it?": room, placement and a neighbour
    NEARBY = "nearby"
    SUPPORT = "support"  # "what is it on?"
    CATEGORY = "category"  # "what kind of chair is it?"
    DESCRIPTION = "description"


class OtherTopic(StrEnum):
    """Questions outside the three core types that privileged knowledge can still answer."""

    AGENT_ROOM = "agent room"
    DISTANCE = "distance"
    PROGRESS = "progress"
    VISIBILITY = "visibility"
    UNKNOWN = "unknown"


class StepChoice(StrEnum):
    """The action a step question proposes ("should I turn left?")."""

    LEFT = "left"
    RIGHT = "right"
    FORWARD = "forward"
    STOP = "stop"


Topic = RouteKind | AttributeTopic | OtherTopic
TOPICS: dict[QuestionType, tuple[Topic, ...]] = {
    QuestionType.ATTRIBUTE: tuple(AttributeTopic),
    QuestionType.ROUTE: tuple(RouteKind),
    QuestionType.DISAMBIGUATION: (),
    QuestionType.OTHER: tuple(OtherTopic),
}
LABELS: tuple[str, ...] = tuple(
    f"{kind.value}:{topic.value}" if topic is not None else kind.value
    for kind, topics in TOPICS.items()
    for topic in (topics or (None,))
)


def label_of(question_type: QuestionType, topic: Topic | None) -> str:
    """The classifier label of a type and topic (``topic`` is None for disambiguation)."""
    return question_type.value if topic is None else f"{question_type.value}:{topic.value}"


def parse_label(label: str) -> tuple[QuestionType, Topic | None]:
    """The type and topic a label names; raises ValueError for a label not in :data:`LABELS`."""
    if label not in LABELS:
        raise ValueError(f"unknown question label {label!r}; labels are {LABELS}")
    kind, _, name = label.partition(":")
    question_type = QuestionType(kind)
    topic = next((t for t in TOPICS[question_type] if t.value == name), None)
    return question_type, topic
