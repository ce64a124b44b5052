"""The whole pipeline: stages present, resume after a kill, shards, settings guard."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.datagen.conftest import SMALL, dataset_files
from vlln.cli import main
from vlln.datagen.build import BuildConfig, BuildSummary, build_dataset, check_settings, summarize
from vlln.datagen.house_locks import lock_houses
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.errors import ConfigError
from vlln.eval.sharding import Shard
from vlln.tasks.episode import read_episodes
from vlln.tasks.splits import house_seeds
from vlln.world.catalogue import default_catalogue


@pytest.mark.slow
def test_every_stage_is_written(small_dataset: Path) -> None:
    houses = list(house_folders(small_dataset))
    assert [h.name for h in houses] == sorted(
        p.name for p in (small_dataset / "scene_summary").iterdir()
    )
    for folder in houses:
        data = HouseDataset(folder)
        assert data.info["attempted"] == SMALL.per_house
        kept = data.info["total_episodes"]
        assert kept + sum(data.info["rejections"].values()) == SMALL.per_house
        assert [row["episode_index"] for row in data.episodes] == list(range(kept))
        for row in data.episodes:
            frames = data.frames(row["episode_index"])
            assert len(frames["action"]) == row["length"]
            assert frames["action"][0] == -1  # no action led to the first frame
            for camera in ("level", "down"):
                assert data.rgb(camera, row["episode_index"], row["length"] - 1).shape == (
                    480,
                    640,
                    3,
                )
    for task in ("iign", "ign", "objectnav"):
        assert read_episodes(small_dataset / "episodes" / f"train_{task}.json.gz")


@pytest.mark.slow
def test_the_summary_counts_the_houses_and_their_disk(small_dataset: Path) -> None:
    summary = summarize(small_dataset)
    infos = [HouseDataset(folder).info for folder in house_folders(small_dataset)]
    assert summary.attempted == sum(info["attempted"] for info in infos) == 2
    assert summary.kept == sum(info["total_episodes"] for info in infos) >= 1
    files = (small_dataset / "trajectories").rglob("*")
    assert summary.disk_bytes >= sum(p.stat().st_size for p in files if p.is_file())
    assert f"kept {summary.kept} of 2 trajectories" in summary.line()


@pytest.mark.slow
def test_the_commands_report_what_they_wrote(
    small_dataset: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The build (here resuming a finished dataset, a copy of the shared one) ends with
    kept/attempted and the disk used; the export of what it built writes conversations."""
    data, export = tmp_path / "data", tmp_path / "export"
    shutil.copytree(small_dataset, data)
    build = ["data", "build", "--houses", "2", "--per-house", "1", "--preset", "small", "--quiet"]
    assert main([*build, "--out", str(data)]) == 0
    assert summarize(data).line() in capsys.readouterr().out
    assert main(["data", "export-sft", str(data), "--out", str(export), "--quiet"]) == 0
    assert "conversations from" in capsys.readouterr().out
    assert (export / "export.json").exists() and (export / "sft.jsonl").stat().st_size > 0


@pytest.mark.slow
def test_a_killed_build_resumes_shard_by_shard_to_the_same_dataset(
    small_dataset: Path, tmp_path: Path
) -> None:
    """A build killed in its first house, resumed as shard 1/2 and then shard 0/2: the
    folder is the uninterrupted build's, byte for byte."""
    out = tmp_path / "resumed"
    command = [sys.executable, "-m", "vlln.cli", "data", "build"]
    command += ["--houses", str(SMALL.houses), "--per-house", str(SMALL.per_house)]
    command += ["--preset", "small", "--out", str(out), "--quiet"]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    journal = out / "trajectories" / "house_00000" / "meta" / "journal.jsonl"
    deadline = time.monotonic() + 240
    while not journal.exists() and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert process.poll() is None, "the build ended before it could be killed"
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    second = out / "trajectories" / "house_00001" / "meta" / "info.json"
    assert not second.exists()
    build_dataset(out, SMALL, shard=Shard(1, 2), progress=False)
    assert second.exists()
    build_dataset(out, SMALL, shard=Shard(0, 2), progress=False)
    assert dataset_files(out) == dataset_files(small_dataset)


@pytest.mark.slow
def test_other_settings_in_the_same_folder_are_refused(small_dataset: Path) -> None:
    with pytest.raises(ConfigError, match="per_house"):
        build_dataset(
            small_dataset, BuildConfig(houses=2, per_house=3, preset="small"), progress=False
        )


def test_a_folder_built_from_another_catalogue_is_refused(tmp_path: Path) -> None:
    config = BuildConfig(houses=1, preset="small")
    check_settings(tmp_path, config)
    recorded = json.loads((tmp_path / "build.json").read_text())
    assert recorded["catalogue"] == default_catalogue().fingerprint()
    recorded["catalogue"] = "an older catalogue"
    (tmp_path / "build.json").write_text(json.dumps(recorded))
    with pytest.raises(ConfigError, match="catalogue"):
        check_settings(tmp_path, config)


def test_bad_settings_are_refused() -> None:
    with pytest.raises(ConfigError, match=r"^houses: Input should be greater than or equal to 1"):
        BuildConfig.build({"houses": 0}, flags=False)


# Another build holding the first shard's houses, as `vlln data build --shard 0/2` would.
_HOLDER = """
import sys
from pathlib import Path
from vlln.datagen.build import BuildConfig
from vlln.datagen.house_locks import lock_houses
from vlln.eval.sharding import Shard
from vlln.tasks.splits import house_seeds
config = BuildConfig(houses=2, per_house=1, preset="small")
with lock_houses(Path(sys.argv[1]), Shard(0, 2).take(house_seeds("train", 2)), config.scene_id):
    print("held", flush=True)
    sys.stdin.read()
"""


@pytest.mark.slow
def test_a_build_of_houses_another_build_holds_stops_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "data"
    holder = subprocess.Popen(
        [sys.executable, "-c", _HOLDER, str(out)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout is not None and holder.stdout.readline() == "held\n"
        build = [
            "data",
            "build",
            "--houses",
            "2",
            "--per-house",
            "1",
            "--preset",
            "small",
            "--quiet",
        ]
        assert main([*build, "--out", str(out)]) == 2
        err = capsys.readouterr().err.splitlines()  # the estimate, then the error
        assert len(err) == 2 and "Traceback" not in err[0]
        assert err[1].startswith("error: another data build is writing vlln/house_00000")
        assert not (out / "trajectories").exists() and not (out / "episodes").exists()
        # The other shard's houses are free: shards still build side by side.
        with lock_houses(out, Shard(1, 2).take(house_seeds("train", 2)), SMALL.scene_id):
            pass
    finally:
        assert holder.stdin is not None
        holder.stdin.close()
        holder.wait(timeout=30)
    with lock_houses(out, house_seeds("train", 2), SMALL.scene_id):  # released at its end
        pass


def test_a_build_that_kept_nothing_says_where_to_look() -> None:
    assert BuildSummary(2, 0, 0, 0).line().endswith("none kept: `vlln data stats` shows why")
    assert "none kept" not in BuildSummary(2, 1, 90, 10**6).line()
