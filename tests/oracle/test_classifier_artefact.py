"""The question classifier's artefact: deterministic training, faithful loading, clear errors."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse

from oracle_training.question_sets import load_named_set
from oracle_training.training import (
    WEIGHT_LEVELS,
    train_artefact,
    training_digest,
    training_questions,
    training_texts,
)
from vlln.cli import main
from vlln.errors import DataFormatError
from vlln.oracle.classifier.model import (
    FEATURE_SETS,
    FORMAT,
    analyser,
    artefact_text,
    classifier_from_bytes,
    load_classifier,
    packaged_artefact_path,
    packaged_classifier,
    packed,
    vectoriser,
)
from vlln.oracle.topics import LABELS

# Every label, a few questions each: enough to fit, quick to train twice.
SMALL = [q for label in LABELS for q in [q for q in training_questions() if q.label == label][:6]]
_SHIPPED = json.loads(packaged_artefact_path().read_text(encoding="utf-8"))


def test_training_is_deterministic_from_the_seed() -> None:
    first = train_artefact(SMALL, seed=3, digest="d")
    assert train_artefact(SMALL, seed=3, digest="d") == first
    assert train_artefact(SMALL, seed=4, digest="d") != first  # the typo copies differ


def test_the_loaded_model_scores_as_vectorisers_with_its_numbers_do(tmp_path: Path) -> None:
    path = tmp_path / "model.json"
    path.write_bytes(train_artefact(SMALL, seed=0, digest="d"))
    model = load_classifier(path)
    fitted = []
    for name, part in zip(FEATURE_SETS, model.feature_sets, strict=True):
        v = vectoriser(name, vocabulary=sorted(part.index, key=part.index.__getitem__))
        v.idf_ = part.idf
        fitted.append(v)
    for text in ["What colour is the sofa?", "wich way shud i go", "Is THIS the one?!", "zzz"]:
        features = scipy.sparse.hstack([v.transform([text]) for v in fitted]).tocsr()
        expected = features @ model.weights + model.bias
        np.testing.assert_allclose(model.scores(text), expected[0], atol=1e-9)
    assert model.meta["seed"] == 0 and model.meta["training_digest"] == "d"


def test_the_analysers_split_texts_as_scikit_learns_do() -> None:
    """Every tenth training question, a few with typo copies, and texts with odd words:
    one-letter words (a padded word shorter than the n-gram), digits, markup, accents and no
    words at all."""
    texts = [q.question for q in training_questions()[::10]] + training_texts(SMALL)[0]
    texts += ["a b I?", "Is it 2 m away?", "<b>Which</b> way?!", "Ça va, café?", "", " ?? "]
    for name in FEATURE_SETS:
        ours, theirs = analyser(name), vectoriser(name).build_analyzer()
        assert [ours(text) for text in texts] == [theirs(text) for text in texts], name


def test_classifying_does_not_import_scikit_learn() -> None:
    code = (
        "import sys; from vlln.oracle.classifier.model import packaged_classifier;"
        "packaged_classifier().predict('What colour is it?');"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('sklearn', 'pandas')))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"


def test_the_artefact_keeps_the_fitted_idf_and_the_weights_to_a_step() -> None:
    raw = json.loads(train_artefact(SMALL, seed=0))
    model = classifier_from_bytes(json.dumps(raw).encode())
    texts, _ = training_texts(SMALL, seed=0)
    assert raw["documents"] == len(texts) == 3 * len(SMALL)  # each question, two typo copies
    for name, part in zip(FEATURE_SETS, model.feature_sets, strict=True):
        fitted = vectoriser(name, min_df=2).fit(texts)
        assert part.index and set(part.index) <= set(fitted.vocabulary_)
        columns = [fitted.vocabulary_[gram] for gram in part.index]
        np.testing.assert_allclose(part.idf[list(part.index.values())], fitted.idf_[columns])
    steps = np.asarray(raw["weight_steps"])
    levels = np.rint(model.weights / steps)
    np.testing.assert_allclose(levels * steps, model.weights, atol=1e-12)
    assert np.abs(levels).max() == WEIGHT_LEVELS
    assert (levels != 0).any(axis=1).all()  # n-grams whose weights all round to 0 are left out


def test_the_shipped_artefact_is_small_and_one_key_a_line() -> None:
    text = packaged_artefact_path().read_text(encoding="utf-8")
    assert len(text) < 1_000_000
    assert len(text.splitlines()) == len(json.loads(text)) + 2


def test_the_shipped_artefact_is_trained_on_the_shipped_questions() -> None:
    meta = packaged_classifier().meta
    assert meta["training_digest"] == training_digest()
    assert set(packaged_classifier().labels) == set(LABELS)


@pytest.mark.parametrize(
    ("content", "problem"),
    [
        (None, "is missing"),
        (b"\x1f\x8b not json", "is damaged"),
        (b"{not json", "is damaged"),
        (json.dumps({"format": 99}).encode(), "has format 99"),
        (json.dumps({"format": FORMAT, "labels": []}).encode(), "is damaged"),
        (json.dumps({"format": FORMAT - 1}).encode(), f"format {FORMAT - 1}"),
        (artefact_text({**_SHIPPED, "weights": "not base85"}).encode(), "is damaged"),
        (artefact_text({**_SHIPPED, "weights": packed("not xz data")[4:]}).encode(), "is damaged"),
        (artefact_text({**_SHIPPED, "weights": packed(np.zeros(3, np.int8))}).encode(), "damaged"),
    ],
)
def test_a_bad_artefact_is_one_line_naming_the_fix(
    tmp_path: Path, content: bytes | None, problem: str
) -> None:
    path = tmp_path / "model.json"
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
    monkeypatch.setattr("oracle_training.training.training_questions", lambda: SMALL)
    path = tmp_path / "out" / "model.json"
    assert main(["oracle", "train-classifier", "--out", str(path), "--seed", "1"]) == 0
    assert load_classifier(path).meta["seed"] == 1
    assert str(path) in capsys.readouterr().out


def test_the_report_command_prints_figures_as_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["oracle", "classify-report", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["questions"] == sum(sum(row.values()) for row in report["confusion"].values())
    assert 0.0 < report["accuracy"] <= 1.0
    assert report["classifier"]["training_digest"] == training_digest()
    assert report["questions"] == len(load_named_set("heldout"))  # the held-out set by default
