"""The evaluation runner: plays an agent over a fixed list of episodes, one line per episode,
with an executor that plays the work (:mod:`vlln.eval.executor`, the protocol ``vlln data
build`` shares): :class:`LocalExecutor` in this process, or
:class:`vlln.cluster.evaluation.RayExecutor` on a cluster. The runner alone owns the rest, so
both write the same folder: the plan and its storage in ``run.json``, the check that a resumed
folder holds the same agent and arguments, the done-set, the writer, refusals, progress, and
the summary with the run's health line.

Order: the episodes of the source (a built-in split or an episode file) are grouped by scene,
keeping first appearance, so one simulator serves a whole house; ``--episodes N`` keeps N of
them spread evenly over the scenes (:func:`spread_over_scenes`), ``--shard i/n`` takes every
n-th of them, and each episode is played at every dialog budget before the next one (the
geodesic field of its goals is reused). An executor hands results back in that order, so the
episode lines are in plan order whoever played them; how each line is played and why it does
not depend on what ran before is :mod:`vlln.eval.play`.

Robustness: the servers of a model agent and of the llm oracle must answer before the first
episode, and a server that fails its client's limit of requests in a row
(:class:`~vlln.errors.ServerDownError`) stops the run, the episode in play unwritten. An
episode the environment refuses (:mod:`vlln.tasks.refusal`) is named with the
reason in one line on stderr, kept in ``episodes.refused.jsonl`` (:mod:`vlln.eval.refusals`)
and counted by the run's health; the run goes on with the others. Finished episodes are on
disk before the next result is taken (see :mod:`vlln.eval.results`), and a restart skips them.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from pathlib import Path

from tqdm import tqdm

from vlln.agents.local.batching import BatchingModel
from vlln.agents.registry import make_agent
from vlln.errors import ConfigError, EpisodeRefusedError, ServerDownError
from vlln.eval.config import EvalConfig
from vlln.eval.cost import eval_cost_line
from vlln.eval.executor import Executor
from vlln.eval.health import RunHealth, run_health
from vlln.eval.plan import RunPlan
from vlln.eval.play import (
    AgentFactory,
    OracleFactory,
    Played,
    WorkItem,
    play_in_order,
)
from vlln.eval.refusals import Refusal, append_refusals, read_refusals
from vlln.eval.results import RunDirectory, SkippedLine, load_runs, record_key
from vlln.eval.side_by_side import check_concurrent, play_side_by_side
from vlln.eval.summary import GroupSummary, summarize_run, summary_json, summary_markdown
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.metrics import success
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import default_cache_dir, load_or_build_split
from vlln.tasks.splits import source_split

Commit = Callable[[list[Played]], None]


EvalExecutor = Executor[EvalConfig, WorkItem, Played]
"""An executor of evaluation work (:mod:`vlln.eval.executor`)."""


@dataclass
class LocalExecutor:
    """An :data:`EvalExecutor` that plays in this process, one episode after the other, or
    ``concurrent`` side by side with their model calls batched (:mod:`vlln.eval.side_by_side`;
    the same records). ``scenes`` shares simulators between calls (it is then not closed
    here); ``sweep`` plays an episode's budgets together by prefix sharing where the agent
    allows it (the same records, in less time); ``agent_factory`` defaults to the registry
    with the run's agent options (side by side, to the ``vlln`` agent on the batched model),
    ``oracle_factory`` to the run's oracle settings."""

    scenes: SceneCache | None = None
    agent_factory: AgentFactory | None = None
    oracle_factory: OracleFactory | None = None
    sweep: bool = True
    label: str = ""
    concurrent: int = 1
    on_model_stats: Callable[[BatchingModel], None] | None = None  # side by side: batches

    def _factory(self, config: EvalConfig) -> AgentFactory:
        if self.agent_factory is not None:
            return self.agent_factory
        return partial(make_agent, options=config.agent_options)

    def check(self, config: EvalConfig) -> None:
        check_concurrent(config, self.concurrent)
        if self.concurrent > 1 and self.agent_factory is not None:
            raise ConfigError("episodes played side by side make their own agents")
        self._factory(config)(config.agent, config.seed, config.detector)

    def play(self, config: EvalConfig, items: list[WorkItem], commit: Commit) -> None:
        if self.concurrent > 1:
            for played in play_side_by_side(
                items,
                config,
                self.concurrent,
                self.scenes,
                self.oracle_factory,
                self.sweep,
                self.on_model_stats,
            ):
                commit(played)
            return
        cache = self.scenes if self.scenes is not None else SceneCache(scenes_dir=config.scenes)
        factory = self._factory(config)
        try:
            for played in play_in_order(
                items, config, cache, factory, self.oracle_factory, self.sweep
            ):
                commit(played)
        finally:
            if self.scenes is None:
                cache.close()


@dataclass(frozen=True)
class RunOutcome:
    """What a call of :func:`run_evaluation` did and what the directory now holds."""

    directory: Path
    planned: int  # (episode, budget) pairs of this run (this shard)
    played: int  # played by this call
    seconds: float  # wall time of this call's episodes
    records: list[EpisodeRecord]  # every record in the directory
    summary: list[GroupSummary] | None  # None while no episode has finished
    health: RunHealth  # complete or not, lines skipped, failures by kind
    repaired: list[SkippedLine]  # lines this call cut (torn) or set aside (invalid, repeated)

    @property
    def complete(self) -> bool:
        """Every planned episode line is written or refused."""
        return self.health.complete


def order_by_scene(episodes: Sequence[Episode]) -> list[Episode]:
    """Episodes grouped by scene (scenes in order of first appearance), stable within one."""
    by_scene: dict[str, list[Episode]] = {}
    for episode in episodes:
        by_scene.setdefault(episode.scene_id, []).append(episode)
    return [episode for group in by_scene.values() for episode in group]


def spread_over_scenes(episodes: Sequence[Episode], count: int) -> list[Episode]:
    """``count`` episodes shared as evenly as possible between the scenes (earlier scenes take
    the remainder) and spaced evenly through each scene's list, so a small evaluation still
    visits every house and every kind of target; grouped by scene."""
    if count > len(episodes):
        raise ConfigError(
            f"asked for {count} episodes but the source has only {len(episodes)}; "
            "pass fewer --episodes or more --houses"
        )
    by_scene: dict[str, list[Episode]] = {}
    for episode in episodes:
        by_scene.setdefault(episode.scene_id, []).append(episode)
    groups = list(by_scene.values())
    quotas = [0] * len(groups)
    left = count
    while left > 0:  # hand out one episode per scene per round, skipping full scenes
        for index, group in enumerate(groups):
            if left > 0 and quotas[index] < len(group):
                quotas[index] += 1
                left -= 1
    chosen = []
    for group, quota in zip(groups, quotas, strict=True):
        chosen += [group[k * len(group) // quota] for k in range(quota)]
    return chosen


def plan_work(episodes: Sequence[Episode], config: EvalConfig) -> list[WorkItem]:
    """The (episode, budget) pairs this run plays, in playing order (module doc)."""
    ordered = order_by_scene(episodes)
    if config.episodes is not None:
        ordered = spread_over_scenes(ordered, config.episodes)
    return [
        WorkItem(episode, budget)
        for episode in config.shard.take(ordered)
        for budget in config.budgets
    ]


def plan_of(items: Sequence[WorkItem], episodes: Sequence[Episode], config: EvalConfig) -> RunPlan:
    """The plan of ``items`` (this shard's), knowing the lines of every shard of the run."""
    chosen = len(episodes) if config.episodes is None else config.episodes
    pairs = ((item.episode.scene_id, item.episode.episode_id) for item in items)
    return RunPlan.of(pairs, config, chosen * len(config.budgets))


def load_episodes(
    config: EvalConfig, cache_dir: Path | None = None, progress: bool = True
) -> list[Episode]:
    """The run's episode source: an episode file, or a built-in split (built once, cached)."""
    if config.episode_file is not None:
        episodes = read_episodes(config.episode_file)
        if not episodes:
            raise ConfigError(
                f"{config.episode_file} holds no episodes; pass an episode file with at least one"
            )
        return episodes
    if config.split is None or config.houses is None:
        raise ConfigError("the run names no episode source; give a split or an episode file")
    return load_or_build_split(
        source_split(config.split),
        config.task,
        config.houses,
        cache_dir or default_cache_dir(),
        progress=progress,
        preset=config.preset,
    )


def run_evaluation(
    config: EvalConfig,
    out: Path,
    *,
    cache_dir: Path | None = None,
    stop_after: int | None = None,
    progress: bool = True,
    agent_factory: AgentFactory | None = None,
    oracle_factory: OracleFactory | None = None,
    scenes: SceneCache | None = None,
    sweep: bool = True,
    provenance: dict[str, str | None] | None = None,
    concurrent: int = 1,
    on_model_stats: Callable[[BatchingModel], None] | None = None,
) -> RunOutcome:
    """Play ``config`` in this process into the run directory ``out``, resuming what is
    already there (:class:`LocalExecutor` says what the playing options do)."""
    executor = LocalExecutor(
        scenes, agent_factory, oracle_factory, sweep, "", concurrent, on_model_stats
    )
    return evaluate(
        config,
        out,
        executor,
        oracle_factory=oracle_factory,
        cache_dir=cache_dir,
        stop_after=stop_after,
        progress=progress,
        provenance=provenance,
    )


def evaluate(
    config: EvalConfig,
    out: Path,
    executor: EvalExecutor,
    *,
    oracle_factory: OracleFactory | None = None,
    cache_dir: Path | None = None,
    stop_after: int | None = None,
    progress: bool = True,
    provenance: dict[str, str | None] | None = None,
) -> RunOutcome:
    """Play ``config`` with ``executor`` into the run directory ``out``, resuming what is
    already there.

    ``oracle_factory`` is who answers the agent's questions, when the executor was given one
    (None: the run's oracle settings, :meth:`EvalConfig.oracle_settings`); ``stop_after``
    plays at most that many episode lines in this call (a later call continues);
    ``provenance`` (agent, oracle, backend, model) goes into run.json, by default that of the
    oracle.
    """
    if stop_after is not None and stop_after < 0:
        raise ConfigError(f"stop_after must be >= 0, got {stop_after}")
    run_dir = RunDirectory(out)
    run_dir.check_is_directory()
    executor.check(config)
    if oracle_factory is None and any(budget > 0 for budget in config.budgets):
        config.oracle_settings().check_server()
    episodes = load_episodes(config, cache_dir, progress)
    items = plan_work(episodes, config)
    plan = plan_of(items, episodes, config)
    provenance = provenance or default_provenance(config, oracle_factory)
    run_dir.prepare(config, provenance=provenance, plan=plan)
    played = 0
    started = time.perf_counter()
    with run_dir.writing(plan) as writer:
        repaired = list(writer.skipped)
        done = {record_key(record) for record in writer.records}
        done |= {refusal.key() for refusal in read_refusals(out)}
        remaining = [item for item in items if item.key(config) not in done]
        todo = remaining if stop_after is None else remaining[:stop_after]
        if progress:
            basis = config.preset if config.episode_file is None else "small"
            line = eval_cost_line(len(items), len(items) - len(remaining), config.agent, basis)
            print(line, file=sys.stderr)
        where = f" {executor.label}" if executor.label else ""
        bar = tqdm(
            total=len(items),
            initial=len(items) - len(remaining),
            desc=f"{config.agent} {config.task}{where}",
            unit="ep",
            file=sys.stderr,
            disable=not progress,
            dynamic_ncols=True,
        )

        def commit(results: list[Played]) -> None:
            """Write what came back: records appended, refusals kept and named; a result
            already in the folder (a chunk run twice) is not written again."""
            nonlocal played
            fresh = [result for result in results if _key(result) not in done]
            refusals = [result for result in fresh if isinstance(result, Refusal)]
            for named in dict.fromkeys((r.episode_id, r.scene_id, r.reason) for r in refusals):
                tqdm.write(f"refused: {EpisodeRefusedError(*named)}", file=sys.stderr)
            append_refusals(out, refusals)
            for result in fresh:
                done.add(_key(result))
                if isinstance(result, EpisodeRecord):
                    writer.append(result)
                    played += 1
                bar.update(1)
            bar.set_postfix(sr=f"{_success_rate(writer.records):.1f}%")

        stopped: ServerDownError | None = None
        with bar:
            try:
                executor.play(config, todo, commit)
            except ServerDownError as error:
                stopped = error
        records = list(writer.records)
    seconds = time.perf_counter() - started
    outcome = finish_run(out, len(items), played, seconds, records, repaired)
    if stopped is not None:  # raised once the summary tells what the finished lines hold
        raise stopped
    return outcome


def finish_run(
    out: Path,
    planned: int,
    played: int,
    seconds: float,
    records: list[EpisodeRecord],
    repaired: list[SkippedLine],
) -> RunOutcome:
    """Write the summary files of the run in ``out`` (with its health) and say what it holds."""
    health = run_health(load_runs([out], whole=False))  # this shard's own health
    summary = summarize_run(records) if records else None
    if summary is not None:
        RunDirectory(out).write_summary(
            summary_json(summary) | {"health": health.to_json()},
            summary_markdown(summary) + f"\n{health.line()}\n",
        )
    return RunOutcome(out, planned, played, seconds, records, summary, health, repaired)


def default_provenance(
    config: EvalConfig, oracle_factory: OracleFactory | None
) -> dict[str, str | None]:
    """Who played and who answered: the agent, and the oracle when any budget has dialog."""
    dialog = any(budget > 0 for budget in config.budgets)
    backend: str | None
    if oracle_factory is None:
        settings = config.oracle_settings()
        oracle, backend = settings.oracle_name, settings.backend_name
    else:
        oracle = getattr(oracle_factory, "__name__", type(oracle_factory).__name__)
        backend = "rules" if oracle_factory is RuleOracle else None
    return {
        "agent": config.agent,
        "oracle": (oracle if dialog else "none"),
        "backend": backend if dialog else "none",
        "model": config.agent_options.get("model"),
    }


def _key(result: Played) -> tuple[str, str, int, str, str]:
    return result.key() if isinstance(result, Refusal) else record_key(result)


def _success_rate(records: Sequence[EpisodeRecord]) -> float:
    return 100.0 * sum(success(record) for record in records) / max(1, len(records))
