"""Ray: a local two-CPU cluster plays an evaluation (refused episodes included) and builds a
dataset like a local run, folder for folder, and a worker killed in the middle of a chunk
costs nothing but time."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path
from typing import Any

import psutil
import pytest
import ray

from tests.conftest import ONE_HOUSE
from vlln.cluster.data import build_dataset_ray
from vlln.cluster.evaluation import run_ray_evaluation
from vlln.datagen.layout import INFO_FILE
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.run_dir import EPISODES_FILE, REFUSED_FILE, RUN_FILE, SUMMARY_JSON, SUMMARY_MD
from vlln.eval.runner import run_evaluation
from vlln.tasks.episode import write_episodes
from vlln.tasks.split_files import load_or_build_split

TASK_TITLE = "ray::play_eval_chunk"  # the process title of a worker playing a chunk


@pytest.fixture(scope="module")
def cluster() -> Iterator[None]:
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


def _kill_a_worker_playing_a_chunk(stop: threading.Event) -> list[int]:
    """Start a thread that SIGKILLs the first worker it finds busy with a chunk.

    It does not wait for a result to be written first: on a busy machine the few short chunks
    could all finish before the hunt caught one of them."""
    killed: list[int] = []

    def hunt() -> None:
        while not stop.is_set():
            for process in psutil.process_iter(["cmdline"]):
                cmdline = process.info["cmdline"] or [""]
                if cmdline[0].startswith(TASK_TITLE):
                    process.kill()
                    killed.append(process.pid)
                    return
            time.sleep(0.01)

    threading.Thread(target=hunt, daemon=True).start()
    return killed


def _lines(folder: Path) -> list[str]:
    return (folder / EPISODES_FILE).read_text(encoding="utf-8").splitlines()


@pytest.mark.slow
def test_one_plan_on_both_executors_writes_the_same_folder_refusals_included(
    cluster: None, split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Three episodes at two budgets, the second lifted 3 m off the floor (on no storey, so
    refused): the Ray run's run.json, episode lines, refusals and summaries are the local
    run's, byte for byte, and both name the refused episode."""
    episodes = load_or_build_split("test", "iign", 1, split_cache, progress=False)[:3]
    x, y, z = episodes[1].start_position
    episodes[1] = replace(episodes[1], start_position=(x, y + 3.0, z))
    path = tmp_path / "iign.json.gz"
    write_episodes(path, episodes)
    config = EvalConfig(
        agent="random",
        task="iign",
        split=None,
        episode_file=str(path),
        budgets=(0, 1),
        max_steps=60,
        preset="small",
    )
    local = run_evaluation(config, tmp_path / "local", progress=False)
    local_err = capsys.readouterr().err
    remote = run_ray_evaluation(config, tmp_path / "ray", episodes_per_chunk=2, progress=False)
    remote_err = capsys.readouterr().err
    refused = f"refused: episode {episodes[1].episode_id} in {episodes[1].scene_id} is refused"
    assert refused in local_err and refused in remote_err
    assert remote.health.refused == local.health.refused == 2
    assert remote.complete and remote.played == local.played == 4
    assert remote.health.line() == local.health.line()
    for name in (RUN_FILE, EPISODES_FILE, REFUSED_FILE, SUMMARY_JSON, SUMMARY_MD):
        assert (tmp_path / "ray" / name).read_bytes() == (tmp_path / "local" / name).read_bytes()
    again = run_ray_evaluation(config, tmp_path / "ray", progress=False)
    assert again.played == 0 and again.complete  # refusals are not played again
    with pytest.raises(ConfigError, match="other settings"):
        run_ray_evaluation(config.replace(max_steps=61), tmp_path / "ray", progress=False)


@pytest.mark.slow
def test_a_killed_worker_is_retried_and_the_folder_equals_a_local_run(
    cluster: None, split_cache: Path, tmp_path: Path
) -> None:
    settings: dict[str, Any] = {
        "agent": "random",
        "task": "iign",
        "houses": 1,
        "episodes": 5,
        "budgets": (0, 1),
        "max_steps": 150,
        "preset": "small",
    }
    config = EvalConfig(**settings)
    local = run_evaluation(config, tmp_path / "local", cache_dir=split_cache, progress=False)
    stop = threading.Event()
    killed = _kill_a_worker_playing_a_chunk(stop)
    try:
        outcome = run_ray_evaluation(
            config,
            tmp_path / "ray",
            cache_dir=split_cache,
            episodes_per_chunk=1,
            max_retries=2,
            progress=False,
        )
    finally:
        stop.set()
    assert killed, "no worker was caught playing a chunk"
    assert outcome.complete and outcome.played == local.planned == 10
    assert _lines(tmp_path / "ray") == _lines(tmp_path / "local")
    summary = (tmp_path / "ray" / SUMMARY_JSON).read_text(encoding="utf-8")
    assert summary == (tmp_path / "local" / SUMMARY_JSON).read_text(encoding="utf-8")
    again = run_ray_evaluation(config, tmp_path / "ray", cache_dir=split_cache, progress=False)
    assert again.played == 0 and _lines(tmp_path / "ray") == _lines(tmp_path / "local")


@pytest.mark.slow
def test_data_build_on_ray_equals_a_local_build(
    cluster: None, one_house_dataset: Path, tmp_path: Path
) -> None:
    config, local = ONE_HOUSE, one_house_dataset  # built by build_dataset in this process
    remote = build_dataset_ray(tmp_path / "ray", config, progress=False)

    def files(root: Path) -> dict[str, bytes]:
        return {
            str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()
        }

    assert files(remote) == files(local)
    assert any(name.endswith(INFO_FILE) for name in files(remote))
    with pytest.raises(ConfigError, match="other settings"):  # the runner's check, on Ray too
        build_dataset_ray(tmp_path / "ray", config.replace(seed=1), progress=False)
