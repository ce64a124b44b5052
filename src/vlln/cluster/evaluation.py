"""``vlln eval --ray``: the evaluation runner's executor for a Ray cluster.

The runner (:mod:`vlln.eval.runner`) plans, resumes, writes and summarises exactly as for a
local run; this executor only plays: chunks hold whole episodes (all their budgets, so the
MSP sweep shares prefixes on the worker) in plan order, one Ray task per chunk, and their
results (records, or refusals of an unplayable episode) go back to the runner in plan order,
so the folder is what ``vlln eval`` without ``--ray`` writes. A worker keeps one scene cache
for all the chunks it plays. The ``vlln`` agent's model is loaded once per node, by a server
its workers share (:mod:`vlln.cluster.model_server`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from vlln.agents.model.agent import ModelAgent
from vlln.agents.protocol import Agent
from vlln.agents.registry import make_agent
from vlln.cluster.model_server import (
    ModelServerLost,
    ServedModel,
    ServerStats,
    served_model,
    server_for_this_node,
    start_model_servers,
    stop_model_servers,
)
from vlln.cluster.options import ServingOptions
from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES, collect_in_order, connect, remote_function
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig
from vlln.eval.play import Played, WorkItem, by_episode, play_in_order
from vlln.eval.runner import Commit, RunOutcome, evaluate
from vlln.tasks.scenes import SceneCache

_worker_scenes: SceneCache | None = None  # one per worker process, kept between its chunks


def play_eval_chunk(
    config: EvalConfig, items: list[WorkItem], sweep: bool, servers: Mapping[str, Any]
) -> list[Played]:
    """The Ray task: play one chunk with this worker's scene cache, a model agent's model on
    the node's server when ``servers`` has any (:mod:`vlln.cluster.model_server`)."""
    global _worker_scenes
    scenes_dir = None if config.scenes is None else Path(config.scenes)
    if _worker_scenes is None or _worker_scenes.scenes_dir != scenes_dir:
        if _worker_scenes is not None:
            _worker_scenes.close()
        _worker_scenes = SceneCache(scenes_dir=scenes_dir)
    model = ServedModel(server_for_this_node(servers)) if servers else None
    factory = None if model is None else partial(_served_agent, model)
    played = [
        result
        for group in play_in_order(items, config, _worker_scenes, factory, sweep=sweep)
        for result in group
    ]
    if model is not None and model.lost is not None:
        raise ModelServerLost(model.lost)  # the chunk is re-run, its results never written
    return played


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


@dataclass
class RayExecutor:
    """An :data:`~vlln.eval.runner.EvalExecutor` that plays on a Ray cluster (module doc):
    ``address`` as for :func:`vlln.cluster.scheduler.connect`, ``episodes_per_chunk`` whole
    episodes per task, each retried ``max_retries`` times when its worker dies; a model
    agent's model is served once per node (``serving``), and ``on_model_stats`` hears what
    the servers did."""

    address: str | None = None
    episodes_per_chunk: int = 4
    max_retries: int = DEFAULT_MAX_RETRIES
    sweep: bool = True
    serving: ServingOptions | None = None
    on_model_stats: Callable[[list[ServerStats]], None] | None = None
    label: str = "on Ray"

    def check(self, config: EvalConfig) -> None:
        if served_model(config) is None:  # checks a served model's options without loading it
            make_agent(config.agent, config.seed, config.detector, config.agent_options)
        chunk_work([], self.episodes_per_chunk)
        connect(self.address)  # an unreachable cluster fails early too

    def play(self, config: EvalConfig, items: list[WorkItem], commit: Commit) -> None:
        ray = connect(self.address)
        model = served_model(config)
        chunks = chunk_work(items, self.episodes_per_chunk)
        task = remote_function(play_eval_chunk, self.max_retries, retry_on=(ModelServerLost,))
        servers: dict[str, Any] = {}
        if model is not None and chunks:
            serving = self.serving or ServingOptions()
            servers = start_model_servers(model, serving, self.max_retries)
        try:
            config_ref = ray.put(config)
            refs = [task.remote(config_ref, chunk, self.sweep, servers) for chunk in chunks]
            collect_in_order(refs, lambda _, played: commit(played))
        finally:
            stats = stop_model_servers(servers)
            if servers and self.on_model_stats is not None:
                self.on_model_stats(stats)


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
    """Play ``config`` on a Ray cluster into ``out`` with the evaluation runner (a rerun
    resumes; :class:`RayExecutor` says what the options do)."""
    executor = RayExecutor(address, episodes_per_chunk, max_retries, sweep, serving, on_model_stats)
    return evaluate(config, out, executor, cache_dir=cache_dir, progress=progress)
