"""``vlln eval --agent vlln --concurrent N``: episodes played side by side with their model
calls batched write the records of one-at-a-time play, in plan order, and a run stopped
part-way resumes (also replayed from its run.json) to the same records."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from vlln.cli import main


def _lines(run: Path) -> list[dict[str, Any]]:
    """The episode lines, each model call's latency (a timing) left out."""
    lines = []
    for text in (run / "episodes.jsonl").read_text(encoding="utf-8").splitlines():
        line = json.loads(text)
        for call in line["model_calls"]:
            del call["latency_ms"]
        lines.append(line)
    return lines


@pytest.mark.slow
def test_side_by_side_play_writes_the_records_of_one_at_a_time_play(
    tiny_model: Path, split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    common = ["eval", "--agent", "vlln", "--model", str(tiny_model), "--task", "iign"]
    common += ["--houses", "1", "--episodes", "4", "--budgets", "0,2", "--max-steps", "6"]
    common += ["--preset", "small", "--max-tokens", "16", "--quiet"]
    common += ["--cache-dir", str(split_cache)]
    alone, together = tmp_path / "alone", tmp_path / "together"
    assert main([*common, "--out", str(alone)]) == 0
    capsys.readouterr()

    assert main([*common, "--out", str(together), "--concurrent", "4", "--stop-after", "3"]) == 0
    assert "3 of 8 episodes" in capsys.readouterr().err
    assert len(_lines(together)) == 3
    replay = ["eval", "--config", str(together / "run.json"), "--out", str(together)]
    assert main([*replay, "--concurrent", "4", "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "8 of 8 episodes" in err

    expected = _lines(alone)
    assert len(expected) == 8 and all(line["model_calls"] for line in expected)
    assert _lines(together) == expected
    # The calls of the episodes in play were answered together.
    stats = re.search(r"model: (\d+) calls in (\d+) batches \(up to (\d+) at once\)", err)
    assert stats is not None
    calls, batches, largest = map(int, stats.groups())
    assert 1 < largest <= 4 and batches < calls
    stored = json.loads((together / "run.json").read_text(encoding="utf-8"))
    assert "concurrent" not in stored  # how a run is played is not one of its settings


def test_side_by_side_play_is_for_agents_with_a_batched_model(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    common = ["eval", "--task", "iign", "--houses", "1", "--episodes", "1", "--quiet"]
    common += ["--cache-dir", str(tmp_path / "splits"), "--out", str(tmp_path / "run")]
    assert main([*common, "--agent", "expert", "--concurrent", "2"]) == 2
    assert "--concurrent 2 batches the model calls of --agent vlln" in capsys.readouterr().err
    assert main([*common, "--agent", "expert", "--concurrent", "0"]) == 2
    assert "--concurrent" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()
