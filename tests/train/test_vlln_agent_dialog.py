"""A checkpoint trained only on the export's dialog samples asks the oracle from the first
step of ``vlln eval --agent vlln``, and the records carry its questions and the answers."""

from __future__ import annotations

import json
import shutil
from itertools import pairwise
from pathlib import Path
from typing import Any

import pytest

from vlln.cli import main
from vlln.eval.results import read_records
from vlln.prompt import TalkOutput, read_output


def _questions_only_export(export: Path, out: Path) -> int:
    """A copy of ``export`` with only the opening exchange (prompt, question) of each sample
    whose first answer is a question, and the images those turns show; returns how many
    samples it kept."""
    kept: list[dict[str, Any]] = []
    for line in (export / "sft.jsonl").read_text(encoding="utf-8").splitlines():
        sample = json.loads(line)
        prompt, answer = sample["conversations"][:2]
        if answer["from"] == "gpt" and answer["value"].startswith("<talk>"):
            shown = prompt["value"].count("<image>")
            kept.append(
                {**sample, "conversations": [prompt, answer], "images": sample["images"][:shown]}
            )
    images = sorted({path for sample in kept for path in sample["images"]})
    for path in images:
        (out / path).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(export / path, out / path)
    rows = "".join(json.dumps(sample, ensure_ascii=False) + "\n" for sample in kept)
    (out / "sft.jsonl").write_text(rows, encoding="utf-8")
    summary = json.loads((export / "export.json").read_text(encoding="utf-8"))
    summary["counts"].update(
        samples=len(kept), images=len(images), samples_by_kind={"dialog": len(kept)}
    )
    (out / "export.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return len(kept)


@pytest.mark.slow
def test_a_checkpoint_trained_on_dialog_asks_and_the_answers_are_recorded(
    sft_export: Path, tiny_model: Path, split_cache: Path, tmp_path: Path
) -> None:
    dialog_export = tmp_path / "dialog_export"
    assert _questions_only_export(sft_export, dialog_export) > 0
    trained = tmp_path / "trained"
    train = ["train", "sft", "--data", str(dialog_export), "--model", str(tiny_model)]
    train += ["--out", str(trained), "--max-steps", "60", "--lr", "1e-2", "--workers", "0"]
    assert main([*train, "--logging-steps", "10", "--seed", "0"]) == 0
    losses = [
        entry["loss"] for entry in json.loads((trained / "training.json").read_text())["losses"]
    ]
    assert losses[-1] < losses[0] / 4, losses

    run = tmp_path / "run"
    evaluate = ["eval", "--agent", "vlln", "--model", str(trained), "--task", "iign"]
    evaluate += ["--houses", "1", "--episodes", "1", "--budget", "5", "--max-steps", "3"]
    evaluate += ["--preset", "small"]
    evaluate += ["--cache-dir", str(split_cache), "--out", str(run), "--quiet"]
    assert main(evaluate) == 0

    (record,) = read_records(run / "episodes.jsonl")
    calls = record.model_calls
    outputs = [read_output(call.text or "", look_down=call.look_down) for call in calls]
    questions = [output.question for output in outputs if isinstance(output, TalkOutput)]
    # The model opens with questions; each asked one is its own <talk> output, in order.
    assert isinstance(outputs[0], TalkOutput), calls[0].text
    assert [turn.question for turn in record.dialog] == questions[: len(record.dialog)]
    assert record.actions[: len(record.dialog)] == ["TALK"] * len(record.dialog)
    # The rule oracle answered every question within the budget, and refused any beyond it
    # (a model trained on questions alone may keep asking)...
    within, beyond = record.dialog[: record.budget], record.dialog[record.budget :]
    assert within
    for turn in within:
        assert turn.answered and turn.answer and turn.backend == "rules"
    for turn in beyond:
        assert not turn.answered and turn.question_type == "refused"
    # ...and each answered exchange went into the prompt of the model's next call.
    for before, after in pairwise(calls[: len(within) + 1]):
        assert after.prompt_tokens > before.prompt_tokens
