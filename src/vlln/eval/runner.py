"""The evaluation runner: plays an agent over a fixed list of episodes, one line per episode.

Order: the episodes of the source (a built-in split or an episode file) are grouped by scene,
keeping first appearance, so one simulator serves a whole house; ``--episodes N`` keeps N of
them spread evenly over the scenes (:func:`spread_over_scenes`), ``--shard i/n`` takes every
n-th of them, and each episode is played at
every dialog budget before the next one (the geodesic field of its goals is reused).

Determinism: for every (episode, budget) the agent and the oracle are made afresh with seeds
derived from (``--seed``, scene, episode) by a hash, the same at every budget, so an episode
line depends on nothing that ran before it: one process, many shards, or a resumed run give
identical lines. Where the agent allows it, an episode's budgets are played together by
prefix sharing (:mod:`vlln.eval.sweep`), which gives the same lines.

Simulators: the plan never returns to a scene it has left, so the previous house's simulator
is closed before the next one is built, and memory stays that of one house.

Robustness: an exception inside the agent's ``reset`` or ``act`` ends that episode, recorded
with end reason ``error`` and the exception text, and the run goes on; outputs that are not
actions are failed actions, which the environment records and caps. An episode the
environment refuses (its start or goals not reachable on their own storeys,
:mod:`vlln.tasks.refusal`) is named with the reason in one line on stderr, kept in
``episodes.refused.jsonl`` (:mod:`vlln.eval.refusals`) and counted by the run's health; the run
goes on with the others. Finished episodes are on
disk before the next one starts (see :mod:`vlln.eval.results`), and a restart skips them.
"""

from __future__ import annotations

import hashlib
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

from tqdm import tqdm

from vlln.agents.protocol import Agent, RecordsModelCalls, reported_stop_reason
from vlln.agents.registry import make_agent
from vlln.errors import ConfigError, EpisodeRefusedError
from vlln.eval.config import EvalConfig
from vlln.eval.cost import eval_cost_line
from vlln.eval.health import RunHealth, run_health
from vlln.eval.plan import RunPlan
from vlln.eval.refusals import Refusal, append_refusals, read_refusals
from vlln.eval.results import RecordKey, RunDirectory, SkippedLine, load_runs, record_key
from vlln.eval.summary import GroupSummary, summarize_run, summary_json, summary_markdown
from vlln.eval.sweep import can_sweep, describe_error, play_sweep
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.metrics import success
from vlln.tasks.oracle_protocol import Oracle
from vlln.tasks.record import EpisodeRecord, agent_label
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.split_files import load_or_build_split
from vlln.tasks.test_protocol import source_split

AgentFactory = Callable[[str, int, str | None], Agent]  # (name, seed, detector)
OracleFactory = Callable[[int], Oracle]


@dataclass(frozen=True)
class WorkItem:
    """One episode to play at one dialog budget."""

    episode: Episode
    budget: int

    def key(self, config: EvalConfig) -> RecordKey:
        """The key its record will have (see :func:`vlln.eval.results.record_key`)."""
        return (
            agent_label(config.agent, config.detector),
            config.task,
            self.budget,
            self.episode.scene_id,
            self.episode.episode_id,
        )


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


def derive_seed(seed: int, role: str, scene_id: str, episode_id: str) -> int:
    """A 63-bit seed for ``role`` (agent, oracle) in one episode, the same at every budget:
    budgets differ only by their refusals (common random numbers for the MSP's differences,
    and what lets :mod:`vlln.eval.sweep` share prefixes)."""
    text = f"{seed}|{role}|{scene_id}|{episode_id}"
    return int.from_bytes(hashlib.sha256(text.encode("utf-8")).digest()[:8], "big") >> 1


def default_cache_dir() -> Path:
    """Where built splits are kept: ``$XDG_CACHE_HOME/vlln/episodes`` (~/.cache by default)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "vlln" / "episodes"


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


def play_episode(
    env: NavigationEnv, agent: Agent, agent_name: str, episode_index: int = 0
) -> EpisodeRecord:
    """Play one episode to its end; an exception in the agent ends it as an error. A model
    agent's calls go into the record."""
    observation, _ = env.reset(options={"episode_index": episode_index})

    def record(error: str | None = None) -> EpisodeRecord:
        calls = agent.model_calls() if isinstance(agent, RecordsModelCalls) else []
        return env.record(
            agent_name, error=error, model_calls=calls, stop_reason=reported_stop_reason(agent)
        )

    try:
        agent.reset(env.episode_info())
    except Exception as error:
        return record(describe_error(error, "reset"))
    while True:
        try:
            action = agent.act(observation)
        except Exception as error:
            return record(describe_error(error, "act"))
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            return record()


def run_evaluation(
    config: EvalConfig,
    out: Path,
    *,
    cache_dir: Path | None = None,
    stop_after: int | None = None,
    progress: bool = True,
    agent_factory: AgentFactory | None = None,
    oracle_factory: OracleFactory = RuleOracle,
    scenes: SceneCache | None = None,
    sweep: bool = True,
    provenance: dict[str, str | None] | None = None,
) -> RunOutcome:
    """Play ``config`` into the run directory ``out``, resuming what is already there.

    ``stop_after`` plays at most that many episodes in this call (a later call continues);
    ``scenes`` shares simulators between calls (it is then not closed here); ``sweep`` plays
    an episode's budgets together by prefix sharing where the agent allows it
    (:mod:`vlln.eval.sweep`; the same records, in less time); ``agent_factory`` defaults to
    the registry with the run's agent options; ``provenance`` (agent, oracle, backend, model)
    goes into run.json, by default the rule oracle's.
    """
    if stop_after is not None and stop_after < 0:
        raise ConfigError(f"stop_after must be >= 0, got {stop_after}")
    RunDirectory(out).check_is_directory()
    if agent_factory is None:
        agent_factory = partial(make_agent, options=config.agent_options)
    agent_factory(config.agent, config.seed, config.detector)  # fail before any work
    episodes = load_episodes(config, cache_dir, progress)
    items = plan_work(episodes, config)
    plan = plan_of(items, episodes, config)
    run_dir = RunDirectory(out)
    run_dir.prepare(
        config, provenance=provenance or default_provenance(config, oracle_factory), plan=plan
    )
    task = TaskType.parse(config.task)
    own_scenes = scenes is None
    cache = scenes if scenes is not None else SceneCache(scenes_dir=config.scenes)
    played = 0
    started = time.perf_counter()
    try:
        with run_dir.writing(plan) as writer:
            _check_same_agent(writer.records, config, out)
            repaired = list(writer.skipped)
            done = {record_key(record) for record in writer.records}
            done |= {refusal.key() for refusal in read_refusals(out)}
            remaining = [item for item in items if item.key(config) not in done]
            todo = remaining if stop_after is None else remaining[:stop_after]
            if progress:
                done_lines = len(items) - len(remaining)
                basis = config.preset if config.episode_file is None else "small"
                line = eval_cost_line(len(items), done_lines, config.agent, basis)
                print(line, file=sys.stderr)
            bar = tqdm(
                total=len(items),
                initial=len(items) - len(remaining),
                desc=f"{config.agent} {config.task}",
                unit="ep",
                file=sys.stderr,
                disable=not progress,
                dynamic_ncols=True,
            )
            with bar:
                scene: str | None = None
                for group in by_episode(todo):
                    if scene is not None and group[0].episode.scene_id != scene:
                        cache.close()  # episodes come grouped by scene: free the last house
                    scene = group[0].episode.scene_id
                    try:
                        plays = _play_group(
                            group, config, task, cache, agent_factory, oracle_factory, sweep
                        )
                    except EpisodeRefusedError as refused:
                        tqdm.write(f"refused: {refused}", file=sys.stderr)
                        append_refusals(out, _refusals(group, config, refused.reason))
                        bar.update(len(group))
                        continue
                    for record in plays:
                        writer.append(record)
                        played += 1
                        bar.update(1)
                    bar.set_postfix(sr=f"{_success_rate(writer.records):.1f}%")
            records = list(writer.records)
    finally:
        if own_scenes:
            cache.close()
    seconds = time.perf_counter() - started
    return finish_run(out, len(items), played, seconds, records, repaired)


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


def default_provenance(config: EvalConfig, oracle_factory: OracleFactory) -> dict[str, str | None]:
    """Who played and who answered: the agent, and the oracle when any budget has dialog."""
    dialog = any(budget > 0 for budget in config.budgets)
    oracle = getattr(oracle_factory, "__name__", type(oracle_factory).__name__)
    rules = oracle_factory is RuleOracle
    return {
        "agent": config.agent,
        "oracle": (oracle if dialog else "none"),
        "backend": ("rules" if rules else None) if dialog else "none",
        "model": config.agent_options.get("model"),
    }


def play_items(
    items: Sequence[WorkItem],
    config: EvalConfig,
    scenes: SceneCache,
    agent_factory: AgentFactory | None = None,
    oracle_factory: OracleFactory = RuleOracle,
    sweep: bool = True,
) -> list[EpisodeRecord]:
    """The records of ``items`` in order, as :func:`run_evaluation` plays them (without
    writing them anywhere): what a remote worker runs for its chunk."""
    if agent_factory is None:
        agent_factory = partial(make_agent, options=config.agent_options)
    task = TaskType.parse(config.task)
    return [
        record
        for group in by_episode(items)
        for record in _play_group(group, config, task, scenes, agent_factory, oracle_factory, sweep)
    ]


def by_episode(items: Sequence[WorkItem]) -> list[list[WorkItem]]:
    """Consecutive items of one episode (its budgets) as groups, in order."""
    groups: list[list[WorkItem]] = []
    for item in items:
        if groups and groups[-1][0].episode is item.episode:
            groups[-1].append(item)
        else:
            groups.append([item])
    return groups


def _play_group(
    group: list[WorkItem],
    config: EvalConfig,
    task: TaskType,
    scenes: SceneCache,
    agent_factory: AgentFactory,
    oracle_factory: OracleFactory,
    sweep: bool,
) -> list[EpisodeRecord]:
    """The records of one episode's budgets: by one sweep where possible, else one by one."""
    episode = group[0].episode
    budgets = [item.budget for item in group]
    seed = derive_seed(config.seed, "agent", *_ids(episode))
    agent = agent_factory(config.agent, seed, config.detector)
    task_config = TaskConfig(task=task, max_steps=config.max_steps, dialog_budget=max(budgets))
    oracle = None
    if task_config.dialog_enabled:
        oracle = oracle_factory(derive_seed(config.seed, "oracle", *_ids(episode)))
    oracle_copies = oracle is None or getattr(oracle, "snapshottable", False)
    if not (sweep and oracle_copies and can_sweep(agent, budgets)):
        return [
            _play_item(item, config, task, scenes, agent_factory, oracle_factory) for item in group
        ]
    env = NavigationEnv([episode], task_config, scenes, oracle, privileged=agent.privileged)
    records = play_sweep(env, agent, config.agent, budgets)
    return [replace(records[budget], detector=config.detector) for budget in budgets]


def _refusals(group: list[WorkItem], config: EvalConfig, reason: str) -> list[Refusal]:
    """The refusal of each budget of one refused episode."""
    return [Refusal(*item.key(config), reason) for item in group]


def _ids(episode: Episode) -> tuple[str, str]:
    return episode.scene_id, episode.episode_id


def _play_item(
    item: WorkItem,
    config: EvalConfig,
    task: TaskType,
    scenes: SceneCache,
    agent_factory: AgentFactory,
    oracle_factory: OracleFactory,
) -> EpisodeRecord:
    episode = item.episode

    def seed_for(role: str) -> int:
        return derive_seed(config.seed, role, *_ids(episode))

    agent = agent_factory(config.agent, seed_for("agent"), config.detector)
    task_config = TaskConfig(task=task, max_steps=config.max_steps, dialog_budget=item.budget)
    oracle = oracle_factory(seed_for("oracle")) if task_config.dialog_enabled else None
    env = NavigationEnv([episode], task_config, scenes, oracle, privileged=agent.privileged)
    return replace(play_episode(env, agent, config.agent), detector=config.detector)


def _check_same_agent(records: Sequence[EpisodeRecord], config: EvalConfig, out: Path) -> None:
    """Episode lines of another agent label (one recorded before detectors were named) would
    be played again beside the new ones; refuse instead."""
    wanted = agent_label(config.agent, config.detector)
    other = next((r.agent_label for r in records if r.agent_label != wanted), None)
    if other is not None:
        raise ConfigError(
            f"{out} holds episodes of {other!r}, not {wanted!r} (written by an older vlln?); "
            "use another --out"
        )


def _success_rate(records: Sequence[EpisodeRecord]) -> float:
    return 100.0 * sum(success(record) for record in records) / max(1, len(records))
