"""``vlln train tiny-model``: writes, without downloading anything, the tiny random model the
tests use, which ``vlln train sft --model`` then trains."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import torch
from safetensors.torch import load_file

from vlln.cli import main


@pytest.mark.slow
def test_the_command_writes_the_tiny_model_that_sft_trains(
    tiny_model: Path, sft_export: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "tiny"
    assert main(["train", "tiny-model", "--out", str(out)]) == 0
    assert f"model to {out}" in capsys.readouterr().out
    # The same weights as the tests' model of seed 0.
    written = load_file(out / "model.safetensors")
    fixture = load_file(tiny_model / "model.safetensors")
    assert set(written) == set(fixture)
    assert all(torch.equal(written[name], fixture[name]) for name in fixture)
    assert json.loads((out / "config.json").read_text())["model_type"] == "qwen2_5_vl"

    run = tmp_path / "run"
    train = ["train", "sft", "--data", str(sft_export), "--model", str(out), "--out", str(run)]
    assert main([*train, "--max-steps", "2", "--workers", "0", "--logging-steps", "1"]) == 0
    log = json.loads((run / "training.json").read_text())
    assert log["steps"] == 2 and len(log["losses"]) == 2
    assert (run / "model.safetensors").is_file()


@pytest.mark.slow
def test_a_rerun_replaces_the_model_and_a_foreign_folder_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "tiny"
    assert main(["train", "tiny-model", "--out", str(out), "--seed", "1"]) == 0
    first = load_file(out / "model.safetensors")
    assert main(["train", "tiny-model", "--out", str(out), "--seed", "2"]) == 0
    second = load_file(out / "model.safetensors")
    assert any(not torch.equal(first[name], second[name]) for name in first)

    (out / "notes.txt").write_text("mine")
    capsys.readouterr()
    assert main(["train", "tiny-model", "--out", str(out)]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "holds files this command did not write (notes.txt)" in error
    assert (out / "notes.txt").read_text() == "mine"
    assert all(torch.equal(load_file(out / "model.safetensors")[n], second[n]) for n in second)
