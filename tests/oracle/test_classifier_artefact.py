"""The question classifier's artefact: deterministic training, faithful loading, clear errors."""

from __future__ import annotations

import gzip
import json
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse

from vlln.cli import main
from vlln.errors import DataFormatError
from vlln.oracle.classifier.model import (
    FEATURE_SETS,
    FORMAT,
    load_classifier,
    packaged_classifier,
    vectoriser,
)
from vlln.oracle.classifier.training import train_artefact, training_digest, training_questions
from vlln.oracle.topics import LABELS

# Every label, a few questions each: enough to fit, quick to train twice.
SMALL = [q for label in LABELS for q in [q for q in training_questions() if q.label == label][:6]]


def test_training_is_deterministic_from_the_seed() -> None:
    first = train_artefact(SMALL, seed=3, digest="d")
    assert train_artefact(SMALL, seed=3, digest="d") == first
    assert train_artefact(SMALL, seed=4, digest="d") != first  # the typo copies differ


def test_the_loaded_model_scores_as_the_fitted_vectorisers_do(tmp_path: Path) -> None:
    path = tmp_path / "model.json.gz"
    path.write_bytes(train_artefact(SMALL, seed=0, digest="d"))
    model = load_classifier(path)
    raw = json.loads(gzip.decompress(path.read_bytes()))
    fitted = []
    for name in FEATURE_SETS:
        stored = raw["features"][name]
        v = vectoriser(name, vocabulary=stored["vocabulary"])
        v.idf_ = np.asarray(stored["idf"])
        fitted.append(v)
    weights = np.asarray(raw["weights"]).T
    for text in ["What colour is the sofa?", "wich way shud i go", "Is THIS the one?!", "zzz"]:
        features = scipy.sparse.hstack([v.transform([text]) for v in fitted]).tocsr()
        expected = features @ weights + np.asarray(raw["bias"])
        np.testing.assert_allclose(model.scores(text), expected[0], atol=1e-9)
    assert model.meta["seed"] == 0 and model.meta["training_digest"] == "d"


def test_the_shipped_artefact_is_trained_on_the_shipped_questions() -> None:
    meta = packaged_classifier().meta
    assert meta["training_digest"] == training_digest()
    assert set(packaged_classifier().labels) == set(LABELS)


@pytest.mark.parametrize(
    ("content", "problem"),
    [
        (None, "is missing"),
        (b"not gzip at all", "is damaged"),
        (gzip.compress(b"{not json", mtime=0), "is damaged"),
        (gzip.compress(json.dumps({"format": 99}).encode(), mtime=0), "has format 99"),
        (
            gzip.compress(json.dumps({"format": FORMAT, "labels": []}).encode(), mtime=0),
            "is damaged",
        ),
        (
            gzip.compress(json.dumps({"format": FORMAT - 1}).encode(), mtime=0),
            f"format {FORMAT - 1}",
        ),
    ],
)
def test_a_bad_artefact_is_one_line_naming_the_fix(
    tmp_path: Path, content: bytes | None, problem: str
) -> None:
    path = tmp_path / "model.json.gz"
    if content is not None:
        path.write_bytes(content)
    with pytest.raises(DataFormatError) as raised:
        load_classifier(path)
    message = str(raised.value)
    assert problem in message and "\n" not in message
    assert "vlln oracle train-classifier" in message


def test_the_train_command_writes_a_loadable_artefact(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # The command on a few questions of every label (training on every shipped question is
    # what the leave-one-out and cross-validation tests do).
    monkeypatch.setattr("vlln.oracle.classifier.training.training_questions", lambda: SMALL)
    path = tmp_path / "out" / "model.json.gz"
    assert main(["oracle", "train-classifier", "--out", str(path), "--seed", "1"]) == 0
    assert load_classifier(path).meta["seed"] == 1
    assert str(path) in capsys.readouterr().out


def test_the_report_command_prints_figures_as_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["oracle", "classify-report", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["questions"] == sum(sum(row.values()) for row in report["confusion"].values())
    assert 0.0 < report["accuracy"] <= 1.0
    assert report["classifier"]["training_digest"] == training_digest()
