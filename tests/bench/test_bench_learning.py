"""The training contract in small: a model from scratch that fits the teacher's first
decisions on the exported prompts makes the same decisions when ``vlln eval --agent vlln``
plays the episode, and every prompt it is shown there is, text and image bytes, one it was
trained on. Any drift between what training and evaluation show the model (prompt text,
connectives, dialog answers, history length, images, action decoding) breaks it.

It trains on the opening scan of one trajectory only (its first frames), so that it fits in
seconds; ``vlln bench learning`` is the whole-episode version (docs/learning.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from vlln.bench.learning import PromptMatch, action_agreement, prompt_match, teacher_decisions
from vlln.cli import main
from vlln.datagen.sft import SftConfig, export_sft
from vlln.datagen.sft.source import open_houses, read_trajectories
from vlln.eval.results import read_records
from vlln.sim.agent import Action
from vlln.tasks.episode import read_episodes, write_episodes
from vlln.train.config import TrainConfig
from vlln.train.scratch import build_tiny_model
from vlln.train.sft import train_sft

FRAMES = 12  # the opening scan's turns: the frames trained on and played


def first_frames_export(dataset: Path, out: Path, history: int) -> Path:
    """Every decision of the dataset's frames before :data:`FRAMES`, as the export writes it
    (``--sample-step 1``, every answer heard), the later samples left out."""
    config = SftConfig(sample_step=1, min_answers=6, history_frames=history)
    export_sft(dataset, out, config, progress=False)
    lines = (out / "sft.jsonl").read_text(encoding="utf-8").splitlines()
    kept = [line for line in lines if frame_of(json.loads(line)["id"]) < FRAMES]
    (out / "sft.jsonl").write_text("\n".join(kept) + "\n", encoding="utf-8")
    return out


def frame_of(sample_id: str) -> int:
    return int(sample_id.split("/frame_")[1][:6])


@pytest.mark.slow
def test_a_model_that_fits_its_teacher_decides_alike_in_vlln_eval(
    one_house_dataset: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (teacher,) = [t for house in open_houses(one_house_dataset) for t in read_trajectories(house)]
    assert set(teacher.actions[:FRAMES]) == {Action.TURN_LEFT}  # the scan, as collected
    export = first_frames_export(one_house_dataset, tmp_path / "sft", history=2)
    model = tmp_path / "model"
    settings = {"data_dir": export, "model": str(build_tiny_model(tmp_path / "new"))}
    settings |= {"out_dir": model, "max_steps": 120, "batch_size": 4, "workers": 0}
    settings |= {"learning_rate": 5e-3, "vision_learning_rate": 5e-3, "save_steps": 120}
    train_sft(TrainConfig.build(settings))
    agreement, *_ = action_agreement(model, export, limit=100)
    assert agreement == 100.0, "the model does not fit its teacher on the exported prompts"
    assert len(teacher_decisions(export)) >= 4
    command = ["bench", "agreement", "--model", str(model), "--export", str(export)]
    capsys.readouterr()
    assert main([*command, "--samples", "5", "--json"]) == 0
    printed = {
        f["metric"]: f["value"] for f in map(json.loads, capsys.readouterr().out.split("\n")[:-1])
    }
    assert printed["action_agreement"] == 100.0 and 1 <= printed["decisions"] <= 5

    episodes = tmp_path / "episode.json.gz"
    all_episodes = read_episodes(one_house_dataset / "episodes" / "train_iign.json.gz")
    write_episodes(episodes, [e for e in all_episodes if e.episode_id == teacher.episode_key])
    run = tmp_path / "run"
    command = ["eval", "--agent", "vlln", "--model", str(model), "--task", "iign"]
    command += ["--episode-file", str(episodes), "--budgets", "5", "--max-steps", str(FRAMES)]
    assert main([*command, "--out", str(run), "--quiet"]) == 0

    (record,) = read_records(run / "episodes.jsonl")
    asked = [e.question for e in teacher.exchanges if e.frame == 0]
    assert [turn.question for turn in record.dialog] == asked
    assert record.actions == ["TALK"] * len(asked) + ["TURN_LEFT"] * FRAMES
    replies = [call.text for call in record.model_calls]
    assert replies == [f"<talk>{q}" for q in asked] + ["<move>←←←←"] * (FRAMES // 4)
    assert prompt_match(run, export) == PromptMatch(100.0, len(replies))
