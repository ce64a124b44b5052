"""Large jobs state their cost before they start, and an interactive large build asks first."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.cli import main
from vlln.datagen.cost import build_cost
from vlln.eval.cost import eval_cost_line


def test_build_cost_scales_with_houses_and_trajectories() -> None:
    """Reproduction 9: 20 houses x 20 trajectories is over an hour and many gigabytes."""
    cost = build_cost(20, 20)
    assert cost.trajectories == 400 and cost.large
    assert "71 min" in cost.line() and "1.9 GB" in cost.line()
    assert not build_cost(1, 2).large


def test_eval_states_what_is_left(capsys: pytest.CaptureFixture[str]) -> None:
    line = eval_cost_line(600, 100)
    assert "500 to play" in line and "12 min" in line and "MB of memory" in line
    assert "(frontier agent, small houses)" in line
    expert = eval_cost_line(600, 100, "expert", "mp3d")
    assert "(expert agent, mp3d houses)" in expert and "frontier" not in expert
    assert "time not estimated for agent openai-vlm" in eval_cost_line(10, 0, "openai-vlm")


def test_a_large_interactive_build_asks_and_can_be_declined(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr("sys.stdin.isatty", lambda: True)
    monkeypatch.setattr("builtins.input", lambda prompt: "n")
    out = tmp_path / "data"
    assert main(["data", "build", "--houses", "1000", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "20000 trajectories" in err and "--yes" in err
    assert not out.exists()
