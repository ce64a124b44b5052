"""Measuring the classifier without a held-out file, and the generated training questions."""

from __future__ import annotations

import json

import pytest
from sklearn.model_selection import GroupKFold

from oracle_training import validation
from oracle_training.generator import generated_jsonl, generated_questions
from oracle_training.question_sets import question_set_path
from oracle_training.training import training_sets
from oracle_training.validation import family, grouped_cv, leave_one_out
from vlln.cli import main
from vlln.oracle.classifier.model import prepared
from vlln.oracle.question_set import LabelledQuestion
from vlln.oracle.topics import LABELS

SETS = training_sets()
# Every label, a few questions each from two sets: enough to fit, quick to train.
SMALL = {
    name: [q for label in LABELS for q in [q for q in SETS[name] if q.label == label][:5]]
    for name in ("train", "generated")
}


def test_a_family_is_the_question_with_its_values_as_slots() -> None:
    assert family("Is the sofa red?") == family("is the coffee table light gray")
    assert family("Is the sofa in the bathrom?") == family("Is the bed in the kitchen?")
    assert family("Is the sofa red?") != family("What colour is the sofa?")


def test_grouped_cv_scores_every_question_once_and_keeps_families_whole() -> None:
    report = grouped_cv(SMALL, folds=3, seed=0)
    questions = [q for qs in SMALL.values() for q in qs]
    assert report["questions"] == len(questions)
    assert report["families"] == len({family(q.question) for q in questions})
    assert 0.0 < report["type_accuracy"] <= 1.0
    assert report["label_accuracy"] <= report["type_accuracy"]
    wrong = len(report["misses"])
    assert wrong == round((1 - report["type_accuracy"]) * len(questions))
    groups = [family(q.question) for q in questions]
    for train_at, test_at in GroupKFold(n_splits=3).split(questions, groups=groups):
        assert not {groups[i] for i in train_at} & {groups[i] for i in test_at}


def test_leaving_a_set_out_trains_on_no_question_reading_as_one_of_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    trained: list[LabelledQuestion] = []

    def record(questions: list[LabelledQuestion], seed: int) -> tuple[int, int, list[object]]:
        trained.extend(questions)
        return len(SMALL["generated"]), 0, []

    copy = SMALL["generated"][0]
    sets = {"train": [*SMALL["train"], copy], "generated": SMALL["generated"]}
    monkeypatch.setattr(validation, "_scored", lambda train, test, seed: record(train, seed))
    report = leave_one_out(sets, "generated", seed=0)
    assert report["questions"] == len(SMALL["generated"])
    seen = {prepared(q.question) for q in SMALL["generated"]}
    assert copy not in trained
    assert trained == [q for q in SMALL["train"] if prepared(q.question) not in seen]
    assert len(trained) > len(SMALL["train"]) // 2


@pytest.mark.slow
def test_a_model_trained_without_v6_types_most_of_v6_right() -> None:
    # An honest out-of-sample figure: v6 was written separately from the other sets.
    report = leave_one_out(SETS, "v6", seed=0)
    assert report["type_accuracy"] >= 0.97, report["misses"]


def test_the_cv_command_prints_both_figures(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr("oracle_training.training.training_sets", lambda: SMALL)
    assert main(["oracle", "classify-cv", "--folds", "2", "--leave-out", "train", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["grouped_cv"]["folds"] == 2
    assert report["leave_one_out"]["test_set"] == "train"
    assert main(["oracle", "classify-cv", "--leave-out", "nonsense"]) != 0
    assert "--leave-out 'nonsense'" in capsys.readouterr().err


def test_the_generated_file_is_the_generator_output_of_seed_0() -> None:
    path = question_set_path("generated")
    assert path.read_text(encoding="utf-8") == generated_jsonl(0)
    assert generated_jsonl(1) != generated_jsonl(0)


def test_the_generator_writes_every_label_without_duplicates() -> None:
    rows = generated_questions(0)
    texts = [" ".join(r["question"].lower().split()) for r in rows]
    assert len(set(texts)) == len(texts)
    labels = {q.label for q in SETS["generated"]}
    assert labels == set(LABELS)
    assert all("{" not in r["question"] for r in rows)
    assert all(prepared(r["question"]) for r in rows)
