"""`vlln score`: every metric recomputed offline from episode lines, equal to the run's summary."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from tests.eval.runs import evaluate, summary
from vlln.cli import main
from vlln.eval.sharding import Shard
from vlln.tasks.scenes import SceneCache


@pytest.fixture(scope="module")
def run_dir(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> Path:
    out = tmp_path_factory.mktemp("scored")
    evaluate(out, split_cache, scenes, agent="expert", episodes=3, max_steps=200)
    return out


def score_json(capsys: pytest.CaptureFixture[str], *args: str) -> dict[str, object]:
    assert main(["score", *args, "--json"]) == 0
    data: dict[str, object] = json.loads(capsys.readouterr().out)
    return data


@pytest.mark.slow
def test_score_recomputes_the_summary(run_dir: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert score_json(capsys, str(run_dir)) == summary(run_dir)
    assert main(["score", str(run_dir)]) == 0
    table = capsys.readouterr().out
    assert "| budget 0 | 3 |" in table and "OS radius 3.00 m" in table and "MSP" in table


@pytest.mark.slow
def test_score_merges_shards(
    run_dir: Path,
    tmp_path: Path,
    split_cache: Path,
    scenes: SceneCache,
    capsys: pytest.CaptureFixture[str],
) -> None:
    for index in range(2):
        evaluate(
            tmp_path / str(index),
            split_cache,
            scenes,
            agent="expert",
            episodes=3,
            max_steps=200,
            shard=Shard(index, 2),
        )
    merged = score_json(capsys, str(tmp_path / "0"), str(tmp_path / "1"))
    assert merged == summary(run_dir)
    assert main(["score", str(run_dir), str(tmp_path / "0")]) == 2  # overlapping: refused
    assert "is in both" in capsys.readouterr().err


def test_radii_are_settings(run_dir: Path, capsys: pytest.CaptureFixture[str]) -> None:
    default = score_json(capsys, str(run_dir))
    tight = score_json(capsys, str(run_dir), "--os-radius", "0.5", "--success-radius", "0.01")
    assert tight["os_radius"] == 0.5 and tight["success_radius"] == 0.01
    for budget in ("0", "1"):
        loose_row = default["groups"][0]["budgets"][budget]["overall"]  # type: ignore[index]
        tight_row = tight["groups"][0]["budgets"][budget]["overall"]  # type: ignore[index]
        assert tight_row["os"] <= loose_row["os"]
        assert tight_row["sr"] <= loose_row["sr"]
    assert main(["score", str(run_dir), "--os-radius", "-1"]) == 2
    assert "radius" in capsys.readouterr().err


def test_score_of_an_empty_directory_says_what_to_pass(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["score", str(tmp_path)]) == 2
    assert "holds no episodes.jsonl" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["nan", "inf", "123", "1e5", "true", "null", "a,b"])
def test_a_folder_name_that_reads_as_json_is_a_path(
    name: str,
    run_dir: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    shutil.copytree(run_dir, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    scored = score_json(capsys, name)
    assert scored["groups"][0]["agent"] == "expert"  # type: ignore[index]
