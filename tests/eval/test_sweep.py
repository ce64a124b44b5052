"""The MSP sweep by prefix sharing gives the records of independent runs of every budget."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from tests.eval.runs import evaluate, lines
from vlln.tasks.scenes import SceneCache


def _without_timing(line: str) -> dict[str, Any]:
    record: dict[str, Any] = json.loads(line)
    for turn in record["dialog"]:
        turn.pop("latency_ms", None)
    return record


@pytest.mark.slow
def test_sweep_records_equal_independent_runs(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    settings: dict[str, Any] = {
        "agent": "frontier",
        "episodes": 1,
        "budgets": (0, 1, 2, 3, 4, 5),
        "max_steps": 120,
    }
    swept = evaluate(tmp_path / "sweep", split_cache, scenes, sweep=True, **settings)
    alone = evaluate(tmp_path / "alone", split_cache, scenes, sweep=False, **settings)
    assert swept.complete and alone.complete
    sweep_records = [_without_timing(line) for line in lines(tmp_path / "sweep")]
    alone_records = [_without_timing(line) for line in lines(tmp_path / "alone")]
    assert sweep_records == alone_records
    # The budgets really branched: their dialogs differ, refusals included.
    first = sweep_records[0]["episode_id"]
    dialogs = {json.dumps(r["dialog"]) for r in sweep_records if r["episode_id"] == first}
    assert len(dialogs) >= 3
    assert any(turn["answered"] is False for r in sweep_records for turn in r["dialog"])
