"""``vlln train new-model``: writes, without downloading anything, a random model of a named
size (the tiny one the tests use), which ``vlln train sft --model`` then trains."""

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
    assert main(["train", "new-model", "--out", str(out)]) == 0
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
    assert main(["train", "new-model", "--out", str(out), "--seed", "1"]) == 0
    first = load_file(out / "model.safetensors")
    assert main(["train", "new-model", "--out", str(out), "--seed", "2"]) == 0
    second = load_file(out / "model.safetensors")
    assert any(not torch.equal(first[name], second[name]) for name in first)

    (out / "notes.txt").write_text("mine")
    capsys.readouterr()
    assert main(["train", "new-model", "--out", str(out)]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "holds files this command did not write (notes.txt)" in error
    assert (out / "notes.txt").read_text() == "mine"
    assert all(torch.equal(load_file(out / "model.safetensors")[n], second[n]) for n in second)


@pytest.mark.parametrize("size", ["small", "base"])
def test_each_size_is_a_qwen_model_with_its_resolution_in_the_folder(
    size: str, tmp_path: Path
) -> None:
    """The card and the image processor state the resolution the model is made for, and the
    architecture loads as the agent loads it."""
    from transformers import AutoConfig

    from vlln.agents.local.card import read_card
    from vlln.agents.local.encoding import ChatEncoder
    from vlln.train.scratch import MODEL_SIZES

    shape = MODEL_SIZES[size]
    config = AutoConfig.from_pretrained(build_config_only(tmp_path, size))
    assert config.model_type == "qwen2_5_vl"
    assert config.text_config.hidden_size == shape.hidden
    assert (
        sum(config.text_config.rope_parameters["mrope_section"]) * 2 == shape.hidden // shape.heads
    )
    card = read_card(tmp_path)
    assert (card.size, card.image_max_pixels, card.history_frames) == (size, shape.max_pixels, 8)
    assert ChatEncoder.load(tmp_path).image_processor.size["longest_edge"] == shape.max_pixels


def build_config_only(out: Path, size: str) -> Path:
    """The folder of a model of ``size`` (the base model too: 81 M parameters, 0.3 GB)."""
    from vlln.train.scratch import build_model

    return build_model(out, size)
