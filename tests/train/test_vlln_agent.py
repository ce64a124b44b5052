"""``vlln eval --agent vlln``: a checkpoint written by ``vlln train sft`` plays episodes through
the model-agent loop, and the records carry its outputs, failures and dialog."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.agents.local.card import ModelCard, read_card, write_card
from vlln.cli import main
from vlln.cli.evaluation import _warn_of_other_houses
from vlln.eval.config import EvalConfig
from vlln.eval.results import read_records
from vlln.prompt import ParseFailure, TalkOutput, read_output


@pytest.mark.slow
def test_a_trained_checkpoint_plays_episodes_with_recorded_outputs(
    sft_export: Path,
    tiny_model: Path,
    split_cache: Path,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    trained = tmp_path / "trained"
    train = ["train", "sft", "--data", str(sft_export), "--model", str(tiny_model)]
    train += ["--out", str(trained), "--max-steps", "4", "--lr", "3e-3", "--workers", "0"]
    assert main(train) == 0
    card = read_card(trained)  # what the model was trained with, for the agent to read
    assert (card.houses, card.history_frames, card.trained_steps) == ("small", 8, 4)
    assert card.image_max_pixels == 56 * 56 and card.size == "tiny"
    run = tmp_path / "run"
    evaluate = ["eval", "--agent", "vlln", "--model", str(trained), "--task", "iign"]
    evaluate += ["--houses", "1", "--episodes", "2", "--budget", "5", "--max-steps", "12"]
    evaluate += ["--preset", "small"]
    evaluate += ["--cache-dir", str(split_cache), "--out", str(run), "--quiet"]
    assert main(evaluate) == 0
    printed = capsys.readouterr()
    assert "vlln on IIGN" in printed.out and "warning" not in printed.err

    records = read_records(run / "episodes.jsonl")
    assert len(records) == 2
    for record in records:
        assert record.agent == "vlln" and record.steps > 0
        calls = record.model_calls
        assert calls and all(call.text is not None and call.completion_tokens > 0 for call in calls)
        outputs = [read_output(call.text or "", look_down=call.look_down) for call in calls]
        unreadable = sum(isinstance(output, ParseFailure) for output in outputs)
        assert record.failures.get("parse", 0) >= unreadable
        assert record.actions.count("FAILED:parse") == record.failures.get("parse", 0)
        questions = [output.question for output in outputs if isinstance(output, TalkOutput)]
        assert [turn.question for turn in record.dialog] == questions[: len(record.dialog)]


def test_the_vlln_agent_needs_a_model_folder(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    common = ["eval", "--agent", "vlln", "--task", "iign", "--houses", "1", "--episodes", "1"]
    common += ["--preset", "small"]
    common += ["--cache-dir", str(tmp_path / "splits"), "--quiet"]
    assert main([*common, "--out", str(tmp_path / "a")]) == 2
    assert "the vlln agent needs --model (a model folder" in capsys.readouterr().err
    assert main([*common, "--out", str(tmp_path / "b"), "--model", str(tmp_path)]) == 2
    assert "is not a model folder (no config.json)" in capsys.readouterr().err


def test_eval_warns_when_a_model_is_scored_on_other_houses_than_it_learnt(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    write_card(tmp_path, ModelCard(houses="small"))
    run = {"agent": "vlln", "task": "iign", "agent_options": {"model": str(tmp_path)}}
    _warn_of_other_houses(EvalConfig.build(run))
    assert "trained on small houses and this run scores it on mp3d" in capsys.readouterr().err
    _warn_of_other_houses(EvalConfig.build({**run, "preset": "small"}))
    write_card(tmp_path, ModelCard())  # a checkpoint from elsewhere: nothing known
    _warn_of_other_houses(EvalConfig.build(run))
    assert capsys.readouterr().err == ""
