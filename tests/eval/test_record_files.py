"""Reading results files that were damaged, edited or cut: bad lines are named and skipped,
never crash the reader; a valid finished record is never lost and never counted twice."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path
from typing import Any

import pytest

from tests.tasks.test_metrics import make_record
from vlln.eval.config import EvalConfig
from vlln.eval.results import (
    SKIPPED_FILE,
    RunDirectory,
    read_records,
    record_key,
    scan_records,
)
from vlln.tasks.record import EpisodeRecord


def line(record: EpisodeRecord) -> bytes:
    return json.dumps(record.to_json()).encode() + b"\n"


def good(n: int) -> list[EpisodeRecord]:
    return [make_record(episode_id=f"e{i}") for i in range(n)]


def test_wrong_types_are_skipped_and_named(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    bad = make_record(episode_id="e1").to_json() | {"steps": "lots", "budget": -3}
    path.write_bytes(line(good(1)[0]) + json.dumps(bad).encode() + b"\n" + line(good(3)[2]))
    scan = scan_records(path)
    assert [r.episode_id for r in scan.records] == ["e0", "e2"]
    (skipped,) = scan.skipped
    assert skipped.kind == "invalid" and skipped.line == 2
    assert "episodes.jsonl:2" in skipped.describe() and "'budget'" in skipped.describe()


def test_valid_record_without_newline_is_kept_and_completed(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    path.write_bytes(b"".join(line(r) for r in good(3))[:-1])  # the last newline never written
    assert read_records(path) == good(3)
    assert scan_records(path).skipped == []
    assert read_records(path, repair=True) == good(3)
    assert path.read_bytes() == b"".join(line(r) for r in good(3))


def test_torn_last_line_is_reported(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    whole = b"".join(line(r) for r in good(3))
    path.write_bytes(whole[:-20])
    scan = scan_records(path)
    assert scan.records == good(2)
    assert [s.kind for s in scan.skipped] == ["torn"]


def test_duplicate_lines_count_once(tmp_path: Path) -> None:
    path = tmp_path / "episodes.jsonl"
    path.write_bytes(b"".join(line(r) for r in [*good(2), good(1)[0]]))
    scan = scan_records(path)
    assert scan.records == good(2)
    assert [(s.kind, s.line) for s in scan.skipped] == [("duplicate", 3)]


def test_resume_sets_bad_lines_aside_and_keeps_one_line_per_episode(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path)
    run.prepare(EvalConfig(agent="random", task="iign", preset="small"), planned=3)
    bad = b'{"episode_id": "e1", "steps": "lots"}\n'
    run.episodes_path.write_bytes(line(good(1)[0]) + bad + line(good(1)[0]))
    with run.writing() as writer:
        assert writer.records == good(1)
        assert {s.kind for s in writer.skipped} == {"invalid", "duplicate"}
        writer.append(good(2)[1])
    assert run.episodes_path.read_bytes().count(b"\n") == 2
    assert scan_records(run.episodes_path).records == good(2)
    assert (tmp_path / SKIPPED_FILE).read_bytes() == bad + line(good(1)[0])
    assert scan_records(run.episodes_path).skipped == []


def _mutations(rng: random.Random, base: dict[str, Any]) -> bytes:
    """One damaged or hostile line."""
    choice = rng.randrange(9)
    data = dict(base)
    field = rng.choice(sorted(data))
    if choice == 0:
        data[field] = rng.choice(["lots", -3, None, [], {}, True, 1e308, -0.5])
    elif choice == 1:
        data[field] = math.nan
    elif choice == 2:
        del data[field]
    elif choice == 3:
        return json.dumps(data).encode()[: rng.randrange(1, 60)] + b"\n"
    elif choice == 4:
        return b'{"episode_id": "' + b"x" * 3_000_000 + b'"}\n'
    elif choice == 5:
        return b"[" * 100_000 + b"\n"
    elif choice == 6:
        return bytes(rng.randrange(256) for _ in range(40)).replace(b"\n", b" ") + b"\n"
    elif choice == 7:
        data["dialog"] = [{"step": -1}]
    else:
        return b"\n"
    return json.dumps(data).encode() + b"\n"


@pytest.mark.slow
def test_fuzzed_files_never_crash_lose_or_double_a_valid_record(tmp_path: Path) -> None:
    rng = random.Random(15)
    path = tmp_path / "episodes.jsonl"
    for trial in range(40):
        valid = [make_record(episode_id=f"t{trial}e{i}", path_length=5.0 + i) for i in range(6)]
        chunks: list[bytes] = []
        for record in valid:
            chunks.append(line(record))
            for _ in range(rng.randrange(3)):
                chunks.append(_mutations(rng, record.to_json()))
            if rng.random() < 0.3:
                chunks.append(line(record))  # an exact duplicate
        data = b"".join(chunks)
        if rng.random() < 0.5:
            data = data[:-1]  # the last newline missing
        path.write_bytes(data)
        scan = scan_records(path)
        kept = {record_key(r): r for r in scan.records}
        assert len(kept) == len(scan.records)  # never twice
        for record in valid:  # never lost
            assert kept[record_key(record)] == record
        read_records(path, repair=True)
        assert {record_key(r) for r in scan_records(path).records} == set(kept)
        (tmp_path / SKIPPED_FILE).unlink(missing_ok=True)
