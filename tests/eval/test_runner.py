"""The evaluation runner: resume, repair, sharding, determinism and misbehaving agents."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest

from tests.eval.runs import evaluate, lines, summary
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.health import run_health
from vlln.eval.play import derive_seed
from vlln.eval.results import SKIPPED_FILE, load_runs
from vlln.eval.runner import (
    load_episodes,
    order_by_scene,
    plan_work,
    spread_over_scenes,
)
from vlln.eval.sharding import Shard
from vlln.eval.summary import summarize_run, summary_json
from vlln.tasks.record import EndReason
from vlln.tasks.scenes import SceneCache


@pytest.fixture(scope="module")
def full_run(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> Path:
    """The reference: 4 episodes x budgets 0 and 1, uninterrupted."""
    out = tmp_path_factory.mktemp("full")
    outcome = evaluate(out, split_cache, scenes)
    assert outcome.complete and outcome.played == 8
    return out


def keys(run_dir: Path) -> list[tuple[int, str]]:
    return [(r["budget"], r["episode_id"]) for r in map(json.loads, lines(run_dir))]


@pytest.mark.slow
def test_full_run_plays_every_episode_at_every_budget(full_run: Path) -> None:
    played = keys(full_run)
    assert len(played) == len(set(played)) == 8
    assert {budget for budget, _ in played} == {0, 1}
    assert summary(full_run)["groups"][0]["msp"] is not None
    assert "OS radius 3.00 m" in (full_run / "summary.md").read_text()


@pytest.mark.slow
def test_resume_after_a_stop_gives_the_same_lines_and_summary(
    full_run: Path, tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    first = evaluate(tmp_path, split_cache, scenes, stop_after=3)
    assert (first.played, len(first.records), first.complete) == (3, 3, False)
    second = evaluate(tmp_path, split_cache, scenes)
    assert (second.played, second.complete) == (5, True)
    assert lines(tmp_path) == lines(full_run)
    assert (tmp_path / "summary.json").read_bytes() == (full_run / "summary.json").read_bytes()
    assert evaluate(tmp_path, split_cache, scenes).played == 0  # a finished run stays finished


@pytest.mark.slow
def test_truncated_last_line_is_cut_and_its_episode_played_again(
    full_run: Path, tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    evaluate(tmp_path, split_cache, scenes, stop_after=2)
    third = (lines(full_run)[2] + "\n").encode()
    with (tmp_path / "episodes.jsonl").open("ab") as handle:
        handle.write(third[: len(third) // 2])  # killed while writing the third episode
    outcome = evaluate(tmp_path, split_cache, scenes)
    assert outcome.played == 6
    assert lines(tmp_path) == lines(full_run)
    assert summary(tmp_path) == summary(full_run)


@pytest.mark.slow
def test_two_shards_equal_one_full_run(
    full_run: Path, tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    shards = [tmp_path / "0", tmp_path / "1"]
    for index, out in enumerate(shards):
        outcome = evaluate(out, split_cache, scenes, shard=Shard(index, 2))
        assert outcome.played == 4
    assert sorted(lines(shards[0]) + lines(shards[1])) == sorted(lines(full_run))
    contents = load_runs(shards)
    merged = summary_json(summarize_run(contents.records))
    assert merged | {"health": run_health(contents).to_json()} == summary(full_run)
    assert summary(full_run)["health"]["complete"] and contents.planned == 8
    assert set(keys(shards[0])).isdisjoint(keys(shards[1]))


@pytest.mark.slow
def test_shards_left_out_make_the_merge_incomplete(
    full_run: Path, tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    """Two shards of three hold 6 of the run's 8 lines; the merge says which shard is
    missing, and is complete only with all three."""
    shards = [tmp_path / str(index) for index in range(3)]
    for index, out in enumerate(shards):
        outcome = evaluate(out, split_cache, scenes, shard=Shard(index, 3))
        assert outcome.complete  # each shard is complete on its own
    partial = run_health(load_runs(shards[:2]))
    assert (partial.finished, partial.planned, partial.complete) == (6, 8, False)
    assert partial.missing_shards == ("2/3",)
    assert "INCOMPLETE, 6 of 8 episode lines (shards 2/3 not given)" in partial.line()
    whole = run_health(load_runs(shards))
    assert (whole.finished, whole.planned, whole.complete) == (8, 8, True)


@pytest.mark.slow
def test_same_seed_gives_identical_lines_and_another_seed_other_agent_seeds(
    full_run: Path, tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    evaluate(tmp_path, split_cache, scenes)
    assert lines(tmp_path) == lines(full_run)
    assert derive_seed(0, "agent", "s", "e") == derive_seed(0, "agent", "s", "e")
    variants = {
        derive_seed(0, "agent", "s", "e"),
        derive_seed(1, "agent", "s", "e"),
        derive_seed(0, "oracle", "s", "e"),
        derive_seed(0, "agent", "t", "e"),
        derive_seed(0, "agent", "s", "f"),
    }
    assert len(variants) == 5


def test_an_agent_raising_in_act_is_recorded_and_the_run_goes_on(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    outcome = evaluate(tmp_path, split_cache, scenes, agent="raising", episodes=2)
    assert outcome.complete and len(outcome.records) == 4
    for record in outcome.records:
        assert record.end_reason == EndReason.ERROR.value
        assert record.error is not None
        assert "RuntimeError" in record.error and "depth sensor unplugged" in record.error
        assert record.actions == ["TURN_LEFT", "TURN_LEFT"]
    failures = summary(tmp_path)["groups"][0]["budgets"]["0"]["overall"]["failures"]
    assert failures["success"] == 0


def test_garbage_outputs_are_failed_actions(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    outcome = evaluate(tmp_path, split_cache, scenes, agent="garbage", episodes=1, budgets=(0,))
    (record,) = outcome.records
    assert record.failed_actions == 20  # the task's cap on failed actions
    assert record.end_reason == EndReason.ERROR.value and record.error == (
        "20 failed actions (invalid 20), the cap max_failed_actions"
    )
    assert all(action.startswith("INVALID:") for action in record.actions)
    assert record.steps == 20 and record.path_length == 0.0


def test_unknown_agent_fails_before_any_work(tmp_path: Path, split_cache: Path) -> None:
    with pytest.raises(
        ConfigError,
        match=r"unknown agent .*choose one of: aiuta, expert, fbe, frontier, frontier-compare, "
        r"openai-vlm",
    ):
        evaluate(tmp_path / "run", split_cache, SceneCache(), agent="no-such-agent")
    assert not (tmp_path / "run").exists()


def test_unknown_task_names_the_valid_ones() -> None:
    with pytest.raises(ConfigError, match="iign, ign, objectnav"):
        EvalConfig(agent="random", task="pointnav", preset="small")


def test_other_arguments_in_an_existing_run_are_refused(
    full_run: Path, split_cache: Path, scenes: SceneCache
) -> None:
    before = lines(full_run)
    with pytest.raises(ConfigError, match=r"seed: 0 there, 7 now.*another --out"):
        evaluate(full_run, split_cache, scenes, seed=7)
    assert lines(full_run) == before


def test_lines_without_the_detector_are_set_aside_and_played_again(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    common: dict[str, Any] = {"agent": "frontier", "budgets": (0,), "episodes": 1, "max_steps": 5}
    evaluate(tmp_path, split_cache, scenes, **common)
    (line,) = lines(tmp_path)
    old = json.loads(line)
    del old["detector"]  # as written before detectors were recorded
    (tmp_path / "episodes.jsonl").write_text(json.dumps(old) + "\n")
    outcome = evaluate(tmp_path, split_cache, scenes, **common)
    (repaired,) = outcome.repaired
    assert repaired.kind == "another run" and "played by frontier on iign" in repaired.reason
    assert outcome.played == 1 and lines(tmp_path) == [line]
    assert (tmp_path / SKIPPED_FILE).read_text() == json.dumps(old) + "\n"


def test_tasks_without_dialog_run_at_budget_zero_and_resume(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    common: dict[str, Any] = {
        "task": "objectnav",
        "budgets": (0,),
        "episodes": 2,
        "agent": "expert",
    }
    first = evaluate(tmp_path, split_cache, scenes, stop_after=1, **common)
    assert [r.budget for r in first.records] == [0]
    outcome = evaluate(tmp_path, split_cache, scenes, **common)
    assert outcome.played == 1 and outcome.complete
    assert all(r.task == "objectnav" for r in outcome.records)


@pytest.mark.slow
def test_ign_with_budgets_0_to_5_talks_and_reports_msp(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    budgets = tuple(range(6))
    outcome = evaluate(
        tmp_path, split_cache, scenes, agent="frontier", task="ign", budgets=budgets, episodes=1
    )
    assert sorted(r.budget for r in outcome.records) == list(budgets)
    assert {(r.agent_label, r.detector) for r in outcome.records} == {
        ("frontier (truth detector)", "truth")
    }
    data = summary(tmp_path)
    group = data["groups"][0]
    assert (group["task"], group["detector"]) == ("ign", "truth")
    assert group["msp"] is not None
    assert "MSP (budgets 0..5)" in (tmp_path / "summary.md").read_text()
    assert "## frontier (truth detector) on IGN" in (tmp_path / "summary.md").read_text()


@pytest.mark.slow
def test_plan_spreads_n_episodes_and_shards_round_robin(split_cache: Path) -> None:
    config = EvalConfig(
        agent="random", task="iign", houses=1, episodes=5, budgets=(0, 2), preset="small"
    )
    episodes = load_episodes(config, split_cache, progress=False)
    plan = plan_work(episodes, config)
    ordered = order_by_scene(episodes)
    expected = [ordered[k * len(ordered) // 5] for k in range(5)]
    assert [item.episode for item in plan[::2]] == expected
    assert [item.budget for item in plan] == [0, 2] * 5
    sharded = plan_work(episodes, config.replace(shard=Shard(1, 2)))
    assert [item.episode for item in sharded[::2]] == expected[1::2]
    with pytest.raises(ConfigError, match="only"):
        plan_work(episodes[:3], config)


def test_spread_over_scenes_shares_episodes_between_houses(split_cache: Path) -> None:
    config = EvalConfig(agent="random", task="iign", houses=1, preset="small")
    episodes = load_episodes(config, split_cache, progress=False)[:10]
    other = [
        replace(e, scene_id="vlln/house_99999", episode_id=f"o{i}")
        for i, e in enumerate(episodes[:2])
    ]
    chosen = spread_over_scenes([*episodes, *other], 5)
    assert [e.scene_id for e in chosen].count("vlln/house_99999") == 2
    assert len(chosen) == 5 and len({e.episode_id for e in chosen}) == 5


def test_order_by_scene_keeps_first_appearance(split_cache: Path) -> None:
    config = EvalConfig(agent="random", task="iign", houses=1, preset="small")
    a, b, c = load_episodes(config, split_cache, progress=False)[:3]
    other = replace(a, scene_id="vlln/house_99999", episode_id="x")
    assert order_by_scene([a, other, b, c]) == [a, b, c, other]
