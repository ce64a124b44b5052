"""Ray with a model agent: on a local cluster with two workers and a model server, the tiny
Qwen2.5-VL is loaded once and the folder equals a local run; a killed server fails the chunk
using it (no retries) or is restarted, and no episode is lost or changed."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import psutil
import pytest
import ray

from vlln.cluster.evaluation import run_ray_evaluation
from vlln.cluster.model_server import ServerStats
from vlln.cluster.options import ServingOptions
from vlln.cluster.scheduler import ClusterError
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.runner import run_evaluation

CHUNK_TITLE = "ray::play_eval_chunk"
SERVER_TITLE = "ray::ModelServer"


@pytest.fixture(scope="module")
def cluster() -> Iterator[None]:
    """Three CPUs: one for the model server, two for workers playing chunks."""
    ray.init(num_cpus=3, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


@pytest.fixture(scope="module")
def config(tiny_model: Path) -> EvalConfig:
    return EvalConfig(
        agent="vlln",
        task="iign",
        houses=1,
        episodes=4,
        budgets=(5,),
        max_steps=3,
        preset="small",
        agent_options={"model": str(tiny_model), "device": "cpu", "max_tokens": "12"},
    )


@pytest.fixture(scope="module")
def local_run(
    config: EvalConfig, split_cache: Path, tmp_path_factory: pytest.TempPathFactory
) -> Path:
    out = tmp_path_factory.mktemp("local") / "run"
    run_evaluation(config, out, cache_dir=split_cache, progress=False)
    return out


def _records_without_timing(folder: Path) -> list[dict[str, Any]]:
    """The episode lines with each model call's latency (wall time) left out."""
    records = []
    for line in (folder / "episodes.jsonl").read_text(encoding="utf-8").splitlines():
        record = json.loads(line)
        for call in record["model_calls"]:
            call.pop("latency_ms")
        records.append(record)
    return records


def _watch(stop: threading.Event, on_sample: Callable[[list[psutil.Process]], bool]) -> None:
    """Call ``on_sample`` with the processes every 50 ms until it returns True."""

    def watch() -> None:
        while not stop.is_set():
            processes = [
                p for p in psutil.process_iter(["cmdline"]) if (p.info["cmdline"] or [""])[0]
            ]
            if on_sample(processes):
                return
            time.sleep(0.05)

    threading.Thread(target=watch, daemon=True).start()


def _titled(processes: list[psutil.Process], title: str) -> list[psutil.Process]:
    return [p for p in processes if p.info["cmdline"][0].startswith(title)]


def test_a_bad_batch_size_is_one_error_before_any_cluster_starts() -> None:
    with pytest.raises(ConfigError, match="--model-batch: Input should be greater than or equal"):
        ServingOptions(model_batch=0)


@pytest.mark.slow
def test_a_server_nowhere_possible_is_one_error_before_any_episode(
    cluster: None, config: EvalConfig, split_cache: Path, tmp_path: Path
) -> None:
    with pytest.raises(ConfigError, match="no node of the cluster has 1 CPUs and 1 GPUs"):
        run_ray_evaluation(
            config, tmp_path / "run", cache_dir=split_cache, serving=ServingOptions(model_gpus=1)
        )
    assert (tmp_path / "run" / "episodes.jsonl").read_text(encoding="utf-8") == ""


@pytest.mark.slow
def test_two_workers_share_one_model_and_the_folder_equals_a_local_run(
    cluster: None, config: EvalConfig, split_cache: Path, local_run: Path, tmp_path: Path
) -> None:
    busy: list[int] = []
    stop = threading.Event()
    _watch(stop, lambda processes: busy.append(len(_titled(processes, CHUNK_TITLE))) is not None)
    stats: list[ServerStats] = []
    try:
        outcome = run_ray_evaluation(
            config,
            tmp_path / "ray",
            cache_dir=split_cache,
            episodes_per_chunk=1,
            progress=False,
            on_model_stats=stats.extend,
        )
    finally:
        stop.set()
    assert outcome.complete and outcome.played == 4
    assert max(busy) >= 2, "two workers should have played chunks at the same time"
    ((server,),) = [stats]  # one node, one server: the model was loaded once
    assert not server.restarted
    records = _records_without_timing(tmp_path / "ray")
    assert records == _records_without_timing(local_run)
    assert all(call["text"] for record in records for call in record["model_calls"])
    assert server.requests == sum(len(record["model_calls"]) for record in records) > 0
    summary = (tmp_path / "ray" / "summary.json").read_text(encoding="utf-8")
    assert summary == (local_run / "summary.json").read_text(encoding="utf-8")


def _kill_the_server_once(results: Path, after_lines: int) -> tuple[threading.Event, list[int]]:
    """SIGKILL the model server's process once ``results`` has ``after_lines`` lines."""
    killed: list[int] = []

    def kill(processes: list[psutil.Process]) -> bool:
        lines = results.read_text(encoding="utf-8").count("\n") if results.exists() else 0
        if lines < after_lines:
            return False
        for process in _titled(processes, SERVER_TITLE):
            process.kill()
            killed.append(process.pid)
        return bool(killed)

    stop = threading.Event()
    _watch(stop, kill)
    return stop, killed


@pytest.mark.slow
def test_a_killed_model_server_fails_its_chunk_or_is_restarted_and_no_episode_changes(
    cluster: None, config: EvalConfig, split_cache: Path, local_run: Path, tmp_path: Path
) -> None:
    out = tmp_path / "ray"
    expected = {(r["episode_id"], r["budget"]): r for r in _records_without_timing(local_run)}

    # No retries: the server stays dead, the chunk using it fails, and the run stops; only
    # whole episodes (the local run's) were written, none from a model that stopped answering.
    stop, killed = _kill_the_server_once(out / "episodes.jsonl", after_lines=1)
    try:
        with pytest.raises(ClusterError, match="ModelServerLost: the model server died") as error:
            run_ray_evaluation(
                config,
                out,
                cache_dir=split_cache,
                episodes_per_chunk=1,
                max_retries=0,
                progress=False,
            )
    finally:
        stop.set()
    assert killed, "the model server was not caught running"
    assert "\n" not in str(error.value)
    saved = _records_without_timing(out)
    assert 1 <= len(saved) < len(expected)
    assert all(record == expected[record["episode_id"], record["budget"]] for record in saved)

    # Resumed with retries, the server killed again: Ray restarts it, the requests it had in
    # hand are sent again, and the folder equals the local run.
    stop, killed = _kill_the_server_once(out / "episodes.jsonl", after_lines=len(saved))
    stats: list[ServerStats] = []
    try:
        outcome = run_ray_evaluation(
            config,
            out,
            cache_dir=split_cache,
            episodes_per_chunk=1,
            max_retries=2,
            progress=False,
            on_model_stats=stats.extend,
        )
    finally:
        stop.set()
    assert killed, "the model server was not caught running"
    assert outcome.complete and outcome.played == len(expected) - len(saved)
    assert [server.restarted for server in stats] == [True]
    assert sorted(_records_without_timing(out), key=str) == sorted(expected.values(), key=str)
