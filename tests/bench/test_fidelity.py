"""The fidelity benchmark's statistics: intervals and the paired dialog gain."""

from __future__ import annotations

from typing import Any

import pytest

from vlln.bench.fidelity import (
    RUNS,
    comparison_rows,
    dialog_gain,
    fidelity_rows,
    mean_interval,
    success_interval,
)
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.tasks.record import EndReason, EpisodeRecord


def record(episode: str, budget: int, succeeded: bool, **overrides: Any) -> EpisodeRecord:
    values: dict[str, Any] = {
        "episode_id": episode,
        "scene_id": "vlln/mp3d_00076/mp3d_00076.glb",
        "task": "iign",
        "agent": "frontier",
        "budget": budget,
        "object_category": "chair",
        "target_ids": [7],
        "end_reason": EndReason.STOP.value,
        "steps": 20,
        "geodesic_start": 4.0,
        "geodesic_trace": [3.0, 0.1 if succeeded else 6.0],
        "path_length": 5.0,
        "stop_instance_id": 7 if succeeded else 9,
        "stop_instance_category": "chair",
        "target_seen_step": 2,
    }
    values.update(overrides)
    return EpisodeRecord(**values)


def test_wilson_interval_stays_inside_0_100_and_covers_the_rate() -> None:
    none = success_interval(0, 20)
    assert none.value == 0.0 and none.low == 0.0 and 10.0 < none.high < 20.0
    half = success_interval(100, 200)
    assert half.low < 50.0 < half.high and half.high - half.low < 15.0
    assert success_interval(20, 20).high == pytest.approx(100.0)


def test_mean_interval_of_constant_values_is_a_point() -> None:
    assert mean_interval([3.0, 3.0]).low == 3.0
    spread = mean_interval([0.0, 10.0, 20.0])
    assert spread.low < 10.0 < spread.high


def test_dialog_gain_pairs_the_same_episodes() -> None:
    records = [record("1", 0, False), record("1", 5, True), record("2", 0, True)]
    records += [record("2", 5, True), record("3", 5, True)]  # 3 has no budget-0 line
    gain = dialog_gain(records, 0, 5)
    assert gain is not None and gain.value == pytest.approx(50.0)
    assert dialog_gain([record("1", 0, True)], 0, 5) is None


def test_every_baseline_is_compared_with_fbe_on_the_same_episodes() -> None:
    """FBE solves episodes 0-4 of 10; VLFM the same and 5-7, but episode 9 is VLFM's alone
    (FBE never played it), so the pairing sees three more successes in nine shared episodes."""
    records: dict[Any, list[EpisodeRecord]] = {run: [] for run in RUNS}
    for run in RUNS:
        if run.task == "objectnav" and run.agent == "fbe":
            records[run] = [record(str(k), 0, k < 5) for k in range(9)]
        if run.task == "objectnav" and run.agent == "vlfm":
            records[run] = [record(str(k), 0, k < 8) for k in range(10)]
    rows = comparison_rows(records)
    assert [(row["agent"], row["task"]) for row in rows] == [("vlfm (noisy detector)", "objectnav")]
    assert rows[0]["sr_minus_fbe_pp"]["value"] == pytest.approx(33.33)  # type: ignore[index]
    agents = {run.agent for run in RUNS}
    assert {"fbe", "vlfm", "frontier", "expert"} == agents
    for task in ("ign", "iign"):  # ObjectNav has no dialog: there the frontier agent is FBE
        assert {run.agent for run in RUNS if run.task == task} == agents
    assert {run.agent for run in RUNS if run.task == "objectnav"} == agents - {"frontier"}


def test_rows_give_sr_spl_taxonomy_and_gain() -> None:
    iign = next(run for run in RUNS if run.task == "iign" and run.agent == "frontier")
    records = [record(str(k), b, k % 2 == 0 or b == 5) for k in range(10) for b in (0, 5)]
    rows = fidelity_rows(iign, records)
    assert [row.get("budget") for row in rows] == [0, 5, None]
    assert rows[0]["sr"]["value"] == 50.0  # type: ignore[index]
    assert rows[1]["taxonomy"]["SR"] == 100.0  # type: ignore[index]
    assert rows[2]["dialog_gain_pp"]["value"] == 50.0  # type: ignore[index]


def test_the_test_protocol_is_500_episodes_on_the_14_test_houses() -> None:
    config = EvalConfig(agent="random", task="iign", split="test500")
    assert (config.episodes, config.houses) == (500, 14)
    assert EvalConfig(agent="random", task="iign", split="test500", episodes=210).episodes == 210
    with pytest.raises(ConfigError, match="test500 is 500 episodes"):
        EvalConfig(agent="random", task="iign", split="test500", houses=3)
    with pytest.raises(ConfigError, match="test500 is 500 episodes"):
        EvalConfig(agent="random", task="iign", split="test500", episodes=501)


@pytest.mark.slow
def test_the_benchmark_plays_every_run_and_resumes(tmp_path: Any, capsys: Any) -> None:
    """One protocol episode of the small houses per run: every run folder is written, the
    rows cover every task, and a second call plays nothing new."""
    from pathlib import Path

    from vlln.bench.fidelity import run_fidelity_benchmark
    from vlln.bench.settings import FidelityBench
    from vlln.eval.results import RunDirectory

    out, cache = Path(tmp_path) / "fid", Path(tmp_path) / "cache"
    settings = FidelityBench(out=out, episodes=1, preset="small", cache_dir=cache, as_json=True)
    rows = run_fidelity_benchmark(settings)
    assert {row["task"] for row in rows} == {"iign", "ign", "objectnav"}
    assert sum("dialog_gain_pp" in row for row in rows) == 1
    for run in RUNS:
        records = RunDirectory(out / run.folder).records()
        assert len(records) == settings.episodes * len(run.budgets)
    before = {run.folder: (out / run.folder / "episodes.jsonl").read_bytes() for run in RUNS}
    assert run_fidelity_benchmark(settings) == rows
    after = {run.folder: (out / run.folder / "episodes.jsonl").read_bytes() for run in RUNS}
    assert after == before
    assert capsys.readouterr().out.count("\n") == 2 * len(rows)


def test_msp_interval_is_the_papers_msp_over_paired_episodes() -> None:
    from vlln.bench.fidelity import msp_interval
    from vlln.tasks.metrics import msp

    wins = {0: [1, 0, 0, 0], 1: [1, 1, 0, 0], 2: [1, 1, 0, 0], 3: [1, 1, 1, 0]}
    wins |= {4: [1, 1, 1, 0], 5: [1, 1, 1, 1]}
    records = [
        record(str(k), budget, bool(won[k])) for budget, won in wins.items() for k in range(4)
    ]
    records.append(record("9", 0, True))  # played at budget 0 only: not paired
    interval = msp_interval(records, range(6))
    rates = [100.0 * sum(wins[b]) / 4 for b in range(6)]
    assert interval is not None and interval.value == pytest.approx(msp(rates))
    assert interval.low < interval.value < interval.high
    assert msp_interval(records[:4], [0]) is None
