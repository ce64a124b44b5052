"""``vlln eval --ray``: the evaluation runner's work as Ray tasks, written by the driver.

Chunks hold whole episodes (all their budgets, so the MSP sweep shares prefixes on the
worker) in plan order. A worker keeps one scene cache for all the chunks it plays. The driver
resumes like the local runner (episodes already in the folder are not sent), appends each
chunk's records in plan order, never a record whose key is already there, and writes the
summary at the end: the folder is what ``vlln eval`` without ``--ray`` writes. The ``vlln``
agent's model is loaded once per node, by a server its workers share
(:mod:`vlln.cluster.model_server`).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Mapping
from functools import partial
from pathlib import Path
from typing import Any

from tqdm import tqdm

from vlln.agents.model.agent import ModelAgent
from vlln.agents.protocol import Agent
from vlln.agents.registry import make_agent
from vlln.cluster.model_server import (
    ModelServerLost,
    ServedModel,
    ServerStats,
    ServingOptions,
    served_model,
    server_for_this_node,
    start_model_servers,
    stop_model_servers,
)
from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES, collect_in_order, connect, remote_function
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.results import RunDirectory, record_key
from vlln.eval.runner import (
    RunOutcome,
    WorkItem,
    by_episode,
    default_provenance,
    finish_run,
    load_episodes,
    plan_of,
    plan_work,
    play_items,
)
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache

_worker_scenes: SceneCache | None = None  # one per worker process, kept between its chunks


def play_eval_chunk(
    config: EvalConfig, items: list[WorkItem], sweep: bool, servers: Mapping[str, Any]
) -> list[EpisodeRecord]:
    """The Ray task: play one chunk with this worker's scene cache, a model agent's model on
    the node's server when ``servers`` has any (:mod:`vlln.cluster.model_server`)."""
    global _worker_scenes
    if _worker_scenes is None:
        _worker_scenes = SceneCache()
    if not servers:
        return play_items(items, config, _worker_scenes, sweep=sweep)
    model = ServedModel(server_for_this_node(servers))
    records = play_items(items, config, _worker_scenes, partial(_served_agent, model), sweep=sweep)
    if model.lost is not None:
        raise ModelServerLost(model.lost)  # the chunk is re-run, its records never written
    return records


def _served_agent(model: ServedModel, name: str, seed: int, _detector: str | None) -> Agent:
    return ModelAgent(model, seed, name=name)


def chunk_work(items: list[WorkItem], episodes_per_chunk: int) -> list[list[WorkItem]]:
    """Consecutive whole episodes, ``episodes_per_chunk`` to a chunk."""
    if episodes_per_chunk < 1:
        raise ConfigError(f"--chunk must be at least 1 episode, got {episodes_per_chunk}")
    groups = by_episode(items)
    return [
        [item for group in groups[start : start + episodes_per_chunk] for item in group]
        for start in range(0, len(groups), episodes_per_chunk)
    ]


def run_ray_evaluation(
    config: EvalConfig,
    out: Path,
    *,
    address: str | None = None,
    cache_dir: Path | None = None,
    episodes_per_chunk: int = 4,
    max_retries: int = DEFAULT_MAX_RETRIES,
    progress: bool = True,
    sweep: bool = True,
    serving: ServingOptions | None = None,
    on_model_stats: Callable[[list[ServerStats]], None] | None = None,
) -> RunOutcome:
    """Play ``config`` on a Ray cluster into ``out`` (module doc); resumes like the runner.

    A model agent's model is served once per node (``serving``: the servers' resources and
    batch size); ``on_model_stats`` hears what the servers did when the run ends.
    """
    model = served_model(config)  # checks a served model's options without loading it
    if model is None:
        make_agent(config.agent, config.seed, config.detector, config.agent_options)
    ray = connect(address)  # an unreachable cluster fails early too
    episodes = load_episodes(config, cache_dir, progress)
    items = plan_work(episodes, config)
    plan = plan_of(items, episodes, config)
    run_dir = RunDirectory(out)
    run_dir.check_is_directory()
    run_dir.prepare(config, provenance=default_provenance(config, RuleOracle), plan=plan)
    task = remote_function(play_eval_chunk, max_retries, retry_on=(ModelServerLost,))
    played = 0
    started = time.perf_counter()
    with run_dir.writing(plan) as writer:
        repaired = list(writer.skipped)
        done = {record_key(record) for record in writer.records}
        remaining = [item for item in items if item.key(config) not in done]
        chunks = chunk_work(remaining, episodes_per_chunk)
        servers: dict[str, Any] = {}
        if model is not None and chunks:
            servers = start_model_servers(model, serving or ServingOptions(), max_retries)
        config_ref = ray.put(config)
        refs = [task.remote(config_ref, chunk, sweep, servers) for chunk in chunks]
        bar = tqdm(
            total=len(items),
            initial=len(done),
            desc=f"{config.agent} {config.task} on Ray",
            unit="ep",
            file=sys.stderr,
            disable=not progress,
        )

        def commit(_: int, records: list[EpisodeRecord]) -> None:
            nonlocal played
            for record in records:
                key = record_key(record)
                if key not in done:
                    writer.append(record)
                    done.add(key)
                    played += 1
                    bar.update(1)

        try:
            with bar:
                collect_in_order(refs, commit)
        finally:
            stats = stop_model_servers(servers)
            if servers and on_model_stats is not None:
                on_model_stats(stats)
        records = list(writer.records)
    seconds = time.perf_counter() - started
    return finish_run(out, len(items), played, seconds, records, repaired)
