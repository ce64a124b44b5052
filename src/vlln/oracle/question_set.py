"""Labelled navigator questions, and how well the offline classifier types them.

The classifier is a set of hand-tuned patterns, so its accuracy means something only on
questions it was not tuned on. Two sets ship with the package: ``train`` (patterns are tuned
against it) and ``heldout`` (written separately and frozen; it is only ever measured, never
tuned against). Both are JSON Lines, one question a line::

    {"question": "Which way is the sofa?", "type": "route", "route_kind": "orientation"}

``route_kind`` is required for route questions and forbidden otherwise.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

from vlln.errors import ConfigError, DataFormatError
from vlln.oracle.classify import RouteKind, classify_question
from vlln.tasks.oracle_protocol import QuestionType

PACKAGED_SETS = ("train", "heldout")
# A held-out set stops being held out once patterns are tuned on its errors; each replacement
# is a new file, written without looking at the classifier.
_PACKAGED_FILES = {"train": "questions_train.jsonl", "heldout": "questions_heldout_v6.jsonl"}
_FIELDS = frozenset({"question", "type", "route_kind"})


@dataclass(frozen=True)
class LabelledQuestion:
    """A question with the type (and, for route questions, the granularity) it should get."""

    question: str
    question_type: QuestionType
    route_kind: RouteKind | None = None


def packaged_question_set_path(name: str) -> Path:
    """Where the packaged set ``name`` ("train" or "heldout") lives."""
    if name not in PACKAGED_SETS:
        raise ConfigError(f"unknown question set {name!r}; choose one of {PACKAGED_SETS}")
    resource = files("vlln.oracle").joinpath("data", _PACKAGED_FILES[name])
    return Path(str(resource))


def load_packaged_question_set(name: str) -> list[LabelledQuestion]:
    """The packaged set ``name`` ("train" or "heldout")."""
    return load_question_set(packaged_question_set_path(name))


def load_question_set(path: str | Path) -> list[LabelledQuestion]:
    """Every question of a JSON Lines file; blank lines are skipped.

    Raises :class:`DataFormatError` naming the file and line of the first bad row.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise DataFormatError(f"cannot read question set {path}: {error.strerror}") from error
    questions = []
    for number, line in enumerate(text.splitlines(), 1):
        if line.strip():
            questions.append(_parse_row(line, f"{path}:{number}"))
    if not questions:
        raise DataFormatError(f"{path}: no questions; expected one JSON object per line")
    return questions


def _parse_row(line: str, where: str) -> LabelledQuestion:
    try:
        row = json.loads(line)
    except json.JSONDecodeError as error:
        raise DataFormatError(f"{where}: not valid JSON ({error.msg})") from error
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
    if question_type != QuestionType.ROUTE:
        if kind is not None:
            raise DataFormatError(f"{where}: 'route_kind' is only for route questions")
        return LabelledQuestion(question, question_type)
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


def classifier_report(path: str | Path | None = None) -> tuple[float, str]:
    """Accuracy and Markdown confusion table of the offline classifier on a labelled file
    (the packaged held-out set when ``path`` is None)."""
    questions = load_packaged_question_set("heldout") if path is None else load_question_set(path)
    matrix = evaluate_classifier(questions)
    return accuracy_of(matrix), markdown_confusion_table(matrix)
