"""Loading labelled question sets, and the confusion matrix that measures a classifier."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from vlln.errors import ConfigError, DataFormatError
from vlln.oracle.classify import RouteKind
from vlln.oracle.question_set import (
    LabelledQuestion,
    accuracy_of,
    classifier_report,
    confusion_matrix,
    evaluate_classifier,
    load_question_set,
    markdown_confusion_table,
)
from vlln.tasks.oracle_protocol import QuestionType

A, R, D, X = (
    QuestionType.ATTRIBUTE,
    QuestionType.ROUTE,
    QuestionType.DISAMBIGUATION,
    QuestionType.OTHER,
)


def _write(tmp_path: Path, lines: list[str]) -> Path:
    path = tmp_path / "questions.jsonl"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_a_file_loads_into_labelled_questions(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        [
            json.dumps({"question": "What colour is it?", "type": "attribute"}),
            "",
            json.dumps({"question": "Which way?", "type": "route", "route_kind": "orientation"}),
        ],
    )
    assert load_question_set(path) == [
        LabelledQuestion("What colour is it?", A),
        LabelledQuestion("Which way?", R, RouteKind.ORIENTATION),
    ]


@pytest.mark.parametrize(
    ("bad_row", "complaint"),
    [
        ('{"question": "Is it red?", "type": "attribute"', "not JSON"),
        ("[" * 100 + "]" * 100, "nested deeper than 64 levels"),
        ('["Is it red?", "attribute"]', "JSON object"),
        ('{"question": "Is it red?", "type": "colour"}', "'type'"),
        ('{"question": "", "type": "attribute"}', "'question'"),
        ('{"question": "Which way?", "type": "route"}', "route_kind"),
        ('{"question": "Is it red?", "type": "attribute", "route_kind": "path"}', "route_kind"),
        ('{"question": "Is it red?", "type": "attribute", "answer": "yes"}', "unknown fields"),
    ],
)
def test_a_bad_row_is_reported_with_its_file_and_line(
    tmp_path: Path, bad_row: str, complaint: str
) -> None:
    good = json.dumps({"question": "Is this it?", "type": "disambiguation"})
    path = _write(tmp_path, [good, good, bad_row, good])
    with pytest.raises(DataFormatError) as raised:
        load_question_set(path)
    assert f"{path}:3" in str(raised.value)
    assert complaint in str(raised.value)


def test_missing_and_empty_files_are_format_errors(tmp_path: Path) -> None:
    with pytest.raises(DataFormatError, match="cannot read"):
        load_question_set(tmp_path / "absent.jsonl")
    with pytest.raises(DataFormatError, match="no questions"):
        load_question_set(_write(tmp_path, ["", "  "]))


def test_confusion_matrix_counts_a_hand_made_example() -> None:
    truth = [A, A, A, R, R, D, X]
    predicted = [A, A, X, R, D, D, X]
    matrix = confusion_matrix(truth, predicted)
    assert matrix[A] == {A: 2, R: 0, D: 0, X: 1}
    assert matrix[R] == {A: 0, R: 1, D: 1, X: 0}
    assert matrix[D][D] == 1 and matrix[X][X] == 1
    assert sum(sum(row.values()) for row in matrix.values()) == len(truth)
    assert accuracy_of(matrix) == pytest.approx(5 / 7)
    table = markdown_confusion_table(matrix).splitlines()
    assert table[0].startswith("| true \\ predicted | attribute | route")
    assert table[2] == "| attribute | 2 | 0 | 0 | 1 | 0.667 |"
    assert table[3] == "| route | 0 | 1 | 1 | 0 | 0.500 |"
    with pytest.raises(ConfigError):
        confusion_matrix([A], [])


def test_evaluation_uses_the_classifier_it_is_given() -> None:
    questions = [LabelledQuestion("a", A), LabelledQuestion("b", R)]
    assert accuracy_of(evaluate_classifier(questions, lambda _: A)) == 0.5
    assert accuracy_of(confusion_matrix([], [])) == 0.0


def test_classifier_report_measures_a_given_file(tmp_path: Path) -> None:
    path = _write(
        tmp_path,
        [
            json.dumps({"question": "What colour is it?", "type": "attribute"}),
            json.dumps({"question": "How far is it?", "type": "attribute", "topic": "size"}),
        ],
    )
    report = classifier_report(path)
    assert report["accuracy"] == 0.5
    assert report["confusion"]["attribute"] == {
        "attribute": 1,
        "route": 0,
        "disambiguation": 0,
        "other": 1,
    }
    assert "| attribute | 1 | 0 | 0 | 1 | 0.500 |" in report["table"]
    # Only the second question gives a topic, and its type is already wrong.
    assert report["topic_accuracy"] == {"attribute": {"questions": 1, "accuracy": 0.0}}
