"""The recipe's figures are read from real evaluation runs laid out as scripts/cpu-recipe.sh
lays them out: intervals, paired dialog gains and the learning curve."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from vlln.bench.recipe import recipe_figures
from vlln.cli import main
from vlln.errors import ConfigError


def _evaluate(out: Path, cache: Path, agent: str, budgets: str) -> None:
    args = ["eval", "--agent", agent, "--task", "iign", "--houses", "1", "--episodes", "3"]
    args += ["--budgets", budgets, "--max-steps", "60", "--cache-dir", str(cache)]
    assert main([*args, "--preset", "small", "--out", str(out), "--quiet"]) == 0


@pytest.mark.slow
def test_the_figures_of_a_recipe_folder(tmp_path: Path, split_cache: Path) -> None:
    runs = tmp_path / "eval"
    _evaluate(runs / "iign-random", split_cache, "random", "0,5")
    _evaluate(runs / "iign-fbe", split_cache, "fbe", "0,5")
    _evaluate(runs / "curve-250", split_cache, "random", "5")
    agreement = tmp_path / "agreement"
    agreement.mkdir()
    for name, value in (("250-train", 12.5), ("250-heldout", 10.0), ("500-heldout", 7.0)):
        figures = [{"metric": "action_agreement", "value": value, "unit": "%"}]
        figures.append({"metric": "decisions", "value": 200, "unit": "count"})
        lines = "".join(json.dumps(figure) + "\n" for figure in figures)
        (agreement / f"{name}.jsonl").write_text(lines, encoding="utf-8")
    text = recipe_figures(tmp_path)
    rows = [line for line in text.splitlines() if line.startswith("| random |")]
    assert [row.split(" | ")[1:3] for row in rows] == [["0", "3"], ["5", "3"]]
    assert "- random: dialog gain (SR at budget 5 - budget 0, paired)" in text
    assert "- fbe: dialog gain" in text and "model - FBE" not in text  # no model run
    assert "OBJECTNAV" not in text
    curve = [line for line in text.splitlines() if line.startswith(("| 250 |", "| 500 |"))]
    assert [row.split(" | ")[1] for row in curve] == ["3", "0"]
    assert [row.split(" | ")[3:] for row in curve] == [["12.5", "10.0 |"], ["-", "7.0 |"]]
    with pytest.raises(ConfigError, match=r"cpu-recipe\.sh"):
        recipe_figures(tmp_path / "nothing")
