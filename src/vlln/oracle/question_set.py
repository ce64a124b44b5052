"""Labelled navigator questions, and how well the offline classifier types them.

A question set is JSON Lines, one question a line::

    {"question": "Which way is the sofa?", "type": "route", "route_kind": "orientation"}
    {"question": "What colour is it?", "type": "attribute", "topic": "color"}

``route_kind`` is required for route questions and forbidden otherwise; ``topic`` (an
:class:`AttributeTopic` or :class:`OtherTopic`) is optional for attribute and other questions
and forbidden otherwise. Training needs every topic; the held-out set has none.

The classifier's training code and question sets (the held-out one among them) are not part
of the installed package: they live in the repository's ``oracle_training/`` folder, beside
``src/`` (:func:`import_training` makes it importable).
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vlln.errors import ConfigError, DataFormatError
from vlln.files import ReadCap, parse_json
from vlln.oracle.classify import analyse_question, classify_question
from vlln.oracle.topics import AttributeTopic, OtherTopic, RouteKind, Topic, label_of
from vlln.tasks.oracle_protocol import QuestionType

# The repository's training folder, as seen from src/vlln/oracle/ of a checkout.
TRAINING_FOLDER = Path(__file__).resolve().parents[3] / "oracle_training"
# The repository's sets are about 100 kB each, some 1,000 questions of 100 bytes.
_QUESTION_SET_CAP = ReadCap("a question set", 16)
_FIELDS = frozenset({"question", "type", "route_kind", "topic"})
_TOPICS: dict[QuestionType, type[AttributeTopic] | type[OtherTopic]] = {
    QuestionType.ATTRIBUTE: AttributeTopic,
    QuestionType.OTHER: OtherTopic,
}


@dataclass(frozen=True)
class LabelledQuestion:
    """A question with the type (and, for route questions, the granularity) it should get."""

    question: str
    question_type: QuestionType
    route_kind: RouteKind | None = None
    topic: AttributeTopic | OtherTopic | None = None

    @property
    def label(self) -> str | None:
        """The classifier label (``attribute:color``), or None when the topic is not given."""
        topic: Topic | None = self.route_kind or self.topic
        if topic is None and self.question_type != QuestionType.DISAMBIGUATION:
            return None
        return label_of(self.question_type, topic)


def import_training(command: str) -> None:
    """Make the repository's ``oracle_training`` package importable (it is when the checkout is
    on the path); raises :class:`ConfigError` naming ``command`` where this vlln is an install
    without it."""
    if importlib.util.find_spec("oracle_training") is not None:
        return
    if not (TRAINING_FOLDER / "__init__.py").is_file():
        raise ConfigError(
            f"{command} needs the classifier's training code and question sets, which are in "
            "the vlln repository's oracle_training/ folder, not in an installed vlln; run it "
            "from a checkout (pip install -e .)"
        )
    sys.path.append(str(TRAINING_FOLDER.parent))


def heldout_texts(command: str) -> list[str]:
    """The questions of the repository's held-out set (for ``command``'s timings)."""
    import_training(command)
    from oracle_training.question_sets import load_named_set

    return [q.question for q in load_named_set("heldout")]


def load_question_set(path: str | Path) -> list[LabelledQuestion]:
    """Every question of a JSON Lines file; blank lines are skipped.

    Raises :class:`DataFormatError` naming the file and line of the first bad row.
    """
    path = Path(path)
    try:
        data = _QUESTION_SET_CAP.read(path)
    except OSError as error:
        raise DataFormatError(f"cannot read question set {path}: {error.strerror}") from error
    questions = []
    for number, line in enumerate(data.splitlines(), 1):
        if line.strip():
            questions.append(_parse_row(line, f"{path}:{number}"))
    if not questions:
        raise DataFormatError(f"{path}: no questions; expected one JSON object per line")
    return questions


def _parse_row(line: bytes, where: str) -> LabelledQuestion:
    try:
        row = parse_json(line)
    except DataFormatError as error:
        raise DataFormatError(f"{where}: {error}") from None
    if not isinstance(row, dict):
        raise DataFormatError(f"{where}: expected a JSON object, got {type(row).__name__}")
    unknown = sorted(set(row) - _FIELDS)
    if unknown:
        raise DataFormatError(f"{where}: unknown fields {unknown}; allowed: {sorted(_FIELDS)}")
    question = row.get("question")
    if not isinstance(question, str) or not question.strip():
        raise DataFormatError(f"{where}: 'question' must be a non-empty string")
    types = [t.value for t in QuestionType]
    if row.get("type") not in types:
        raise DataFormatError(f"{where}: 'type' must be one of {types}, got {row.get('type')!r}")
    question_type = QuestionType(row["type"])
    kind = row.get("route_kind")
    topics = _TOPICS.get(question_type)
    if row.get("topic") is not None:
        if topics is None:
            raise DataFormatError(f"{where}: 'topic' is only for attribute and other questions")
        if row["topic"] not in [t.value for t in topics]:
            names = [t.value for t in topics]
            raise DataFormatError(f"{where}: 'topic' must be one of {names}, got {row['topic']!r}")
    if question_type != QuestionType.ROUTE:
        if kind is not None:
            raise DataFormatError(f"{where}: 'route_kind' is only for route questions")
        topic = None if topics is None or row.get("topic") is None else topics(row["topic"])
        return LabelledQuestion(question, question_type, topic=topic)
    kinds = [k.value for k in RouteKind]
    if kind not in kinds:
        raise DataFormatError(f"{where}: a route question needs 'route_kind' in {kinds}")
    return LabelledQuestion(question, question_type, RouteKind(kind))


# --- measuring a classifier ----------------------------------------------------------------

ConfusionMatrix = dict[QuestionType, dict[QuestionType, int]]


def confusion_matrix(
    truth: Sequence[QuestionType], predicted: Sequence[QuestionType]
) -> ConfusionMatrix:
    """Counts of (true type -> predicted type) over every pair of types."""
    if len(truth) != len(predicted):
        raise ConfigError(f"{len(truth)} true labels but {len(predicted)} predictions")
    matrix = {t: dict.fromkeys(QuestionType, 0) for t in QuestionType}
    for true_type, predicted_type in zip(truth, predicted, strict=True):
        matrix[true_type][predicted_type] += 1
    return matrix


def accuracy_of(matrix: ConfusionMatrix) -> float:
    """The share of questions on the diagonal (0 for an empty matrix)."""
    total = sum(sum(row.values()) for row in matrix.values())
    correct = sum(matrix[t][t] for t in matrix)
    return correct / total if total else 0.0


def markdown_confusion_table(matrix: ConfusionMatrix) -> str:
    """Rows are true types, columns predicted types, with per-row recall."""
    types = list(QuestionType)
    lines = [
        "| true \\ predicted | " + " | ".join(t.value for t in types) + " | recall |",
        "|---" * (len(types) + 2) + "|",
    ]
    for true_type in types:
        row = matrix[true_type]
        total = sum(row.values())
        recall = f"{row[true_type] / total:.3f}" if total else "-"
        counts = " | ".join(str(row[t]) for t in types)
        lines.append(f"| {true_type.value} | {counts} | {recall} |")
    return "\n".join(lines)


def evaluate_classifier(
    questions: Sequence[LabelledQuestion],
    classify: Callable[[str], QuestionType] = classify_question,
) -> ConfusionMatrix:
    """The confusion matrix of ``classify`` on a labelled set."""
    predicted = [classify(q.question) for q in questions]
    return confusion_matrix([q.question_type for q in questions], predicted)


def predicted_label(text: str) -> str:
    """The label (type and topic) the offline classifier gives ``text``."""
    analysis = analyse_question(text)
    topic: Topic | None = analysis.route_kind or analysis.attribute or analysis.other
    return label_of(analysis.question_type, topic)


def classifier_report(path: str | Path) -> dict[str, Any]:
    """Accuracy on type, confusion matrix and, where the set gives topics, per-type topic
    accuracy of the offline classifier on a labelled file."""
    questions = load_question_set(path)
    matrix = evaluate_classifier(questions)
    topics: dict[str, dict[str, float]] = {}
    for question_type in QuestionType:
        labelled = [q for q in questions if q.question_type == question_type and q.label]
        if labelled and question_type != QuestionType.DISAMBIGUATION:
            right = sum(predicted_label(q.question) == q.label for q in labelled)
            topics[question_type.value] = {
                "questions": len(labelled),
                "accuracy": right / len(labelled),
            }
    return {
        "questions": len(questions),
        "accuracy": accuracy_of(matrix),
        "confusion": {t.value: {p.value: n for p, n in row.items()} for t, row in matrix.items()},
        "topic_accuracy": topics,
        "table": markdown_confusion_table(matrix),
    }
