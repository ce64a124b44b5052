"""Ray: a local two-CPU cluster plays an evaluation and builds a dataset like a local run, and
a worker killed in the middle of a chunk costs nothing but time."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import psutil
import pytest
import ray

from vlln.cluster.data import build_dataset_ray
from vlln.cluster.evaluation import run_ray_evaluation
from vlln.datagen.build import BuildConfig, build_dataset
from vlln.eval.config import EvalConfig
from vlln.eval.runner import run_evaluation
from vlln.tasks.split_files import load_or_build_split

TASK_TITLE = "ray::play_eval_chunk"  # the process title of a worker playing a chunk


@pytest.fixture(scope="module")
def cluster() -> Iterator[None]:
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


@pytest.fixture(scope="module")
def split_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    cache = tmp_path_factory.mktemp("episodes")
    load_or_build_split("test", "iign", 1, cache, progress=False)
    return cache


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
    return (folder / "episodes.jsonl").read_text(encoding="utf-8").splitlines()


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
    summary = (tmp_path / "ray" / "summary.json").read_text(encoding="utf-8")
    assert summary == (tmp_path / "local" / "summary.json").read_text(encoding="utf-8")
    again = run_ray_evaluation(config, tmp_path / "ray", cache_dir=split_cache, progress=False)
    assert again.played == 0 and _lines(tmp_path / "ray") == _lines(tmp_path / "local")


@pytest.mark.slow
def test_data_build_on_ray_equals_a_local_build(cluster: None, tmp_path: Path) -> None:
    config = BuildConfig(houses=1, per_house=1)
    local = build_dataset(tmp_path / "local", config, progress=False)
    remote = build_dataset_ray(tmp_path / "ray", config, progress=False)

    def files(root: Path) -> dict[str, bytes]:
        return {
            str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()
        }

    assert files(remote) == files(local)
    assert any("/meta/info.json" in name for name in files(remote))
