"""``vlln train sft`` on a real export with the tiny model: the loss falls, checkpoints resume,
LoRA merges back into a plain model, the vision tower learns at its own rate."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import torch
from safetensors.torch import load_file

from vlln.cli import main
from vlln.train.optim import is_vision_tower, parameter_groups

FAST = ["--lr", "3e-3", "--vision-lr", "1e-3", "--logging-steps", "2", "--workers", "0"]


def _train(export: Path, model: Path, out: Path, *extra: str) -> dict:
    argv = ["train", "sft", "--data", str(export), "--model", str(model), "--out", str(out)]
    assert main([*argv, *FAST, *extra]) == 0
    return json.loads((out / "training.json").read_text())


@pytest.fixture(scope="module")
def eight_steps(
    sft_export: Path, tiny_model: Path, tmp_path_factory: pytest.TempPathFactory
) -> Path:
    """Eight steps with a checkpoint every four, trained once for the tests that read or
    continue such a run (each continues a copy of its own)."""
    out = tmp_path_factory.mktemp("sft") / "run"
    _train(sft_export, tiny_model, out, "--max-steps", "8", "--save-steps", "4")
    return out


def _copy(run: Path, out: Path) -> Path:
    shutil.copytree(run, out)
    return out


@pytest.mark.slow
def test_loss_falls_and_a_rerun_resumes_from_the_newest_checkpoint(
    eight_steps: Path,
    sft_export: Path,
    tiny_model: Path,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    out = _copy(eight_steps, tmp_path / "run")
    first = json.loads((out / "training.json").read_text())
    losses = [entry["loss"] for entry in first["losses"]]
    assert [entry["step"] for entry in first["losses"]] == [2, 4, 6, 8]
    assert losses[-1] < losses[0] - 0.5, losses
    assert first["steps"] == 8 and first["resumed_from"] is None
    assert {p.name for p in out.glob("checkpoint-*")} == {"checkpoint-4", "checkpoint-8"}
    # A checkpoint is a loadable model folder of its own.
    assert (out / "checkpoint-4" / "tokenizer.json").is_file()
    assert (out / "checkpoint-4" / "preprocessor_config.json").is_file()

    capsys.readouterr()
    second = _train(sft_export, tiny_model, out, "--max-steps", "10", "--save-steps", "4")
    assert "loss " in capsys.readouterr().out
    assert second["resumed_from"] == str(out / "checkpoint-8")
    # The curve goes on from the checkpoint's own log.
    assert second["losses"][:4] == first["losses"]
    assert [entry["step"] for entry in second["losses"]] == [2, 4, 6, 8, 10]


def _same_weights(first: Path, second: Path) -> bool:
    one, other = load_file(first / "model.safetensors"), load_file(second / "model.safetensors")
    return set(one) == set(other) and all(torch.equal(one[name], other[name]) for name in one)


@pytest.mark.slow
def test_a_resumed_run_goes_on_from_the_checkpoints_weights(
    eight_steps: Path, sft_export: Path, tiny_model: Path, tmp_path: Path
) -> None:
    straight, resumed = eight_steps, tmp_path / "resumed"
    first = json.loads((straight / "training.json").read_text())
    checkpoint = straight / "checkpoint-4"
    second = _train(
        sft_export, tiny_model, resumed, "--max-steps", "8", "--resume", str(checkpoint)
    )
    assert second["resumed_from"] == str(checkpoint)
    # Steps 5..8 from the checkpoint's weights, optimizer and data order: the same run.
    assert second["losses"] == first["losses"]
    assert _same_weights(straight, resumed)
    assert not _same_weights(tiny_model, resumed)


FOUR_STEPS = ("--max-steps", "4", "--save-steps", "2", "--logging-steps", "10")  # none logged


@pytest.mark.slow
def test_a_finished_run_rerun_changes_nothing(
    sft_export: Path, tiny_model: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run"
    _train(sft_export, tiny_model, out, *FOUR_STEPS)
    files = {path: path.read_bytes() for path in out.rglob("*") if path.is_file()}
    assert "loss not logged (it is every --logging-steps 10 steps)" in capsys.readouterr().out
    _train(sft_export, tiny_model, out, *FOUR_STEPS)
    assert "already trained to step 4; nothing to do" in capsys.readouterr().out
    assert {path: path.read_bytes() for path in out.rglob("*") if path.is_file()} == files
    # Stopped after the last checkpoint, before the final model: the rerun writes the
    # checkpoint's weights, without another step.
    (out / "model.safetensors").unlink()
    (out / "training.json").unlink()
    summary = _train(sft_export, tiny_model, out, *FOUR_STEPS)
    assert summary["steps"] == 4
    assert _same_weights(out, out / "checkpoint-4")
    assert {p.name for p in out.glob("checkpoint-*")} == {"checkpoint-2", "checkpoint-4"}


@pytest.mark.slow
def test_lora_adapters_are_merged_into_the_saved_model(
    sft_export: Path, tiny_model: Path, tmp_path: Path
) -> None:
    out = tmp_path / "lora"
    _train(sft_export, tiny_model, out, "--lora", "--lora-rank", "4", "--max-steps", "2")
    before, after = (
        load_file(tiny_model / "model.safetensors"),
        load_file(out / "model.safetensors"),
    )
    assert set(after) == set(before)  # a plain model: no adapter weights left
    changed = {name for name in before if not torch.equal(before[name], after[name])}
    # Only the language model's projections learnt; the vision tower is untouched.
    assert changed
    assert all("visual" not in name and name.endswith("_proj.weight") for name in changed)


@pytest.mark.slow
def test_vision_tower_gets_its_own_learning_rate(tiny_model: Path) -> None:
    from transformers import AutoModelForImageTextToText

    model = AutoModelForImageTextToText.from_pretrained(tiny_model)
    groups = parameter_groups(model, 2e-5, 5e-6)
    assert [group["lr"] for group in groups] == [2e-5, 5e-6]
    names = {id(p): name for name, p in model.named_parameters()}
    vision = [names[id(p)] for p in groups[1]["params"]]
    assert vision and all(".visual." in f".{name}" and "merger" not in name for name in vision)
    assert any("visual.merger" in names[id(p)] for p in groups[0]["params"])
    assert not is_vision_tower("model.language_model.layers.0.mlp.gate_proj.weight")


@pytest.mark.slow
@pytest.mark.parametrize(
    "command",
    [
        ["train", "sft", "--data", "d", "--model", "m", "--out", "o"],
        ["eval", "--agent", "vlln", "--model", "m", "--task", "iign", "--out", "o"],
    ],
)
def test_without_the_model_extra_the_command_says_what_to_install(command: list[str]) -> None:
    hide_torch = "import sys; sys.modules['torch'] = None; from vlln.cli import main; "
    result = subprocess.run(
        [sys.executable, "-c", hide_torch + f"sys.exit(main({command!r}))"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 2
    assert result.stderr.splitlines() == [
        "error: the local model needs torch, which is not installed; install the model "
        f"extra with: pip install -e '{Path(__file__).resolve().parents[2]}[model]'"
    ]


@pytest.mark.slow
def test_a_model_that_cannot_be_loaded_is_one_clear_error(
    sft_export: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    for model in (tmp_path / "missing", tmp_path):
        argv = ["train", "sft", "--data", str(sft_export), "--model", str(model)]
        assert main([*argv, "--out", str(tmp_path / "out")]) == 2
        error = capsys.readouterr().err.strip()
        assert error.startswith(f"error: cannot load the model '{model}'")
        assert len(error.splitlines()) == 1
