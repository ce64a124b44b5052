"""The classifier's question sets by name, and the clear error of a vlln without them."""

from __future__ import annotations

from pathlib import Path

import pytest

from oracle_training.question_sets import SETS, TRAINING_SETS, load_named_set, question_set_path
from vlln.cli import main
from vlln.errors import ConfigError
from vlln.oracle import question_set


def test_the_train_set_loads_and_unknown_names_are_refused() -> None:
    assert load_named_set("train")
    with pytest.raises(ConfigError, match="heldout"):
        load_named_set("test")


def test_each_training_set_has_its_own_file() -> None:
    paths = {question_set_path(name) for name in TRAINING_SETS}
    assert len(paths) == len(TRAINING_SETS)
    assert all(question_set_path(name).suffix == ".jsonl" for name in SETS)


def test_the_heldout_set_loads() -> None:
    assert load_named_set("heldout")


def test_the_train_set_repeats_no_row() -> None:
    rows = load_named_set("train")
    assert len(set(rows)) == len(rows)


def test_an_install_without_the_training_folder_says_where_it_is(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(question_set.importlib.util, "find_spec", lambda name: None)
    monkeypatch.setattr(question_set, "TRAINING_FOLDER", tmp_path / "oracle_training")
    with pytest.raises(ConfigError, match="oracle_training/ folder"):
        question_set.import_training("vlln oracle classify-cv")
    assert main(["oracle", "train-classifier", "--out", str(tmp_path / "model.json")]) != 0
    assert "vlln oracle train-classifier needs" in capsys.readouterr().err
    assert not (tmp_path / "model.json").exists()
