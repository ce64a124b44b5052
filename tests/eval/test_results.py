"""The results file and run directory: durable appends, partial-line repair, argument checks."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from tests.tasks.test_metrics import make_record
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.config import EvalConfig, default_budgets, parse_budgets
from vlln.eval.results import (
    RunDirectory,
    load_run_records,
    read_records,
    record_key,
    scan_records,
)
from vlln.eval.sharding import Shard
from vlln.tasks.record import EpisodeRecord


def records(n: int, budget: int = 0) -> list[EpisodeRecord]:
    return [make_record(episode_id=f"e{i}", budget=budget) for i in range(n)]


def write_lines(path: Path, items: list[EpisodeRecord]) -> None:
    path.write_text("".join(json.dumps(r.to_json()) + "\n" for r in items), encoding="utf-8")


def test_append_then_read_round_trips(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path / "run")
    run.prepare(EvalConfig(agent="random", task="iign", preset="small"))
    with run.writing() as writer:
        for record in records(3):
            writer.append(record)
    assert run.records() == records(3)
    assert run.episodes_path.read_bytes().count(b"\n") == 3


def test_partial_last_line_is_ignored_and_cut_on_repair(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    write_lines(path, records(2))
    whole = path.read_bytes()
    path.write_bytes(whole + whole[:40])  # a kill in the middle of the third write
    assert read_records(path) == records(2)
    assert path.read_bytes() != whole  # reading alone leaves the file as it is
    assert read_records(path, repair=True) == records(2)
    assert path.read_bytes() == whole


def test_resume_through_writer_starts_on_a_fresh_line(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path)
    run.prepare(EvalConfig(agent="random", task="iign", preset="small"))
    write_lines(run.episodes_path, records(1))
    with run.episodes_path.open("ab") as handle:
        handle.write(b'{"episode_id": "e1", "sce')
    with run.writing() as writer:
        assert writer.records == records(1)
        writer.append(records(2)[1])
    assert run.records() == records(2)


def test_malformed_complete_line_is_skipped_and_named(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    write_lines(path, records(2))
    path.write_text(path.read_text() + "{not json}\n" + json.dumps(records(3)[2].to_json()) + "\n")
    scan = scan_records(path)
    assert scan.records == records(3)
    assert [s.describe().split(": ")[0] for s in scan.skipped] == [f"{path}:3"]
    path.write_text('{"episode_id": "x"}\n')
    assert "missing field" in scan_records(path).skipped[0].reason


def test_merging_runs_refuses_overlap(tmp_path: Path) -> None:
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    write_lines(tmp_path / "a" / "episodes.jsonl", records(2))
    write_lines(tmp_path / "b" / "episodes.jsonl", records(3)[1:])
    with pytest.raises(ConfigError, match="is in both"):
        load_run_records([tmp_path / "a", tmp_path / "b"])
    write_lines(tmp_path / "b" / "episodes.jsonl", records(2, budget=1))
    merged = load_run_records([tmp_path / "a", tmp_path / "b"])
    assert len({record_key(r) for r in merged}) == 4
    with pytest.raises(ConfigError, match=r"holds no episodes\.jsonl"):
        load_run_records([tmp_path / "missing"])


def test_run_directory_refuses_other_arguments(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path / "run")
    run.prepare(EvalConfig(agent="random", task="iign", seed=0, preset="small"))
    run.prepare(
        EvalConfig(agent="random", task="iign", seed=0, houses=14, preset="small")
    )  # same run
    with pytest.raises(ConfigError, match=r"seed: 0 there, 1 now.*another --out"):
        run.prepare(EvalConfig(agent="random", task="iign", seed=1, preset="small"))


def test_results_without_run_file_are_not_adopted(tmp_path: Path) -> None:
    write_lines(tmp_path / "episodes.jsonl", records(1))
    with pytest.raises(ConfigError, match=r"run.json does not"):
        RunDirectory(tmp_path).prepare(EvalConfig(agent="random", task="iign", preset="small"))


def test_second_writer_is_refused(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path)
    run.prepare(EvalConfig(agent="random", task="iign", preset="small"))
    with run.writing(), pytest.raises(ConfigError, match="another evaluation"), run.writing():
        pass


def test_config_round_trips_and_a_resume_names_what_differs(tmp_path: Path) -> None:
    config = EvalConfig(agent="expert", task="IIGN", budgets=(0, 1, 2), shard=Shard(1, 3))
    assert config.task == "iign"
    assert EvalConfig.from_json(json.loads(json.dumps(config.to_json())), "x") == config
    other = EvalConfig(agent="expert", task="iign", budgets=(5,), shard=Shard(1, 3))
    run = RunDirectory(tmp_path)
    run.prepare(config)
    with pytest.raises(
        ConfigError, match=r"differing: budgets; budgets: \[0, 1, 2\] there, \[5\] now"
    ):
        run.prepare(other)
    with pytest.raises(DataFormatError, match=r"run\.json"):
        EvalConfig.from_json({"agent": "expert"}, "run.json")


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"task": "flying"}, "iign, ign, objectnav"),
        ({"task": "objectnav", "budgets": (5,)}, "no dialog"),
        ({"agent": "frontier", "detector": "yolo"}, r"unknown detector 'yolo'; .*truth, noisy"),
        ({"detector": "noisy"}, "agent 'random' uses no detector"),
        ({"split": "holdout"}, "train, val, test"),
        ({"budgets": (1, 1)}, "repeat"),
        ({"episodes": 0}, "at least 1"),
        ({"split": None}, "exactly one episode source"),
    ],
)
def test_config_rejects_bad_arguments(kwargs: dict[str, Any], message: str) -> None:
    values: dict[str, Any] = {"agent": "random", "task": "iign", **kwargs}
    with pytest.raises(ConfigError, match=message):
        EvalConfig(**values, preset="small")


def test_budgets_and_shards_parse() -> None:
    assert parse_budgets("0-5") == (0, 1, 2, 3, 4, 5)
    assert parse_budgets("0,2,5") == (0, 2, 5)
    assert parse_budgets("3") == (3,)
    assert default_budgets("iign") == (5,) and default_budgets("objectnav") == (0,)
    assert default_budgets("ign") == (0,)  # dialog on IGN only when budgets are given
    with pytest.raises(ConfigError, match="backwards"):
        parse_budgets("5-0")
    with pytest.raises(ConfigError, match="range"):
        parse_budgets("a-b")
    assert Shard.parse(" 1 / 3 ") == Shard(1, 3)
    assert Shard(1, 3).take(list(range(8))) == [1, 4, 7]
    shards = [Shard(i, 3).take(list(range(8))) for i in range(3)]
    assert sorted(x for part in shards for x in part) == list(range(8))
    for bad in ("3/3", "1", "-1/2"):
        with pytest.raises(ConfigError, match="i/n"):
            Shard.parse(bad)
