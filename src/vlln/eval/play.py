"""Playing planned work: what an executor of the runner (:mod:`vlln.eval.runner`) runs, in
this process or on a Ray worker, and what it hands back, in plan order.

Determinism: for every (episode, budget) the agent and the oracle are made afresh with seeds
derived from (``--seed``, scene, episode) by a hash, the same at every budget, so an episode
line depends on nothing that ran before it: one process, many shards, a cluster or a resumed
run give identical lines. Where the agent allows it, an episode's budgets are played together
by prefix sharing (:mod:`vlln.eval.sweep`), which gives the same lines.

Robustness: an exception inside the agent's ``reset`` or ``act`` ends that episode, recorded
with end reason ``error`` and the exception text; outputs that are not actions are failed
actions, which the environment records and caps. An episode the environment refuses (its
start or goals not reachable on their own storeys, :mod:`vlln.tasks.refusal`) comes back as
one :class:`~vlln.eval.refusals.Refusal` per budget instead of records, so the runner records
it the same way whichever executor played it.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from functools import partial

from vlln.agents.protocol import Agent, RecordsModelCalls, reported_stop_reason
from vlln.agents.registry import make_agent
from vlln.errors import EpisodeRefusedError
from vlln.eval.config import EvalConfig
from vlln.eval.refusals import Refusal
from vlln.eval.results import RecordKey
from vlln.eval.sweep import can_sweep, describe_error, play_sweep
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode
from vlln.tasks.oracle_protocol import Oracle
from vlln.tasks.record import EpisodeRecord, agent_label
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import TaskConfig, TaskType

AgentFactory = Callable[[str, int, str | None], Agent]  # (name, seed, detector)
OracleFactory = Callable[[int], Oracle]
Played = EpisodeRecord | Refusal  # what one (episode, budget) of the plan came to


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


def derive_seed(seed: int, role: str, scene_id: str, episode_id: str) -> int:
    """A 63-bit seed for ``role`` (agent, oracle) in one episode, the same at every budget:
    budgets differ only by their refusals (common random numbers for the MSP's differences,
    and what lets :mod:`vlln.eval.sweep` share prefixes)."""
    text = f"{seed}|{role}|{scene_id}|{episode_id}"
    return int.from_bytes(hashlib.sha256(text.encode("utf-8")).digest()[:8], "big") >> 1


def episode_seed(seed: int, role: str, episode: Episode) -> int:
    """:func:`derive_seed` for ``role`` in ``episode`` (what the data build seeds alike)."""
    return derive_seed(seed, role, episode.scene_id, episode.episode_id)


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


def by_episode(items: Sequence[WorkItem]) -> list[list[WorkItem]]:
    """Consecutive items of one episode (its budgets) as groups, in order."""
    groups: list[list[WorkItem]] = []
    for item in items:
        if groups and groups[-1][0].episode is item.episode:
            groups[-1].append(item)
        else:
            groups.append([item])
    return groups


def play_in_order(
    items: Sequence[WorkItem],
    config: EvalConfig,
    scenes: SceneCache,
    agent_factory: AgentFactory | None = None,
    oracle_factory: OracleFactory | None = None,
    sweep: bool = True,
) -> Iterator[list[Played]]:
    """What each episode of ``items`` came to (its budgets' records, or their refusals), one
    episode at a time in order. The plan never returns to a scene it has left, so the last
    house's simulator is closed when the scene changes and memory stays that of one house."""
    play = group_player(config, agent_factory, oracle_factory, sweep)
    scene: str | None = None
    for group in by_episode(items):
        if scene is not None and group[0].episode.scene_id != scene:
            scenes.close()
        scene = group[0].episode.scene_id
        yield play(group, scenes)


GroupPlayer = Callable[[list[WorkItem], SceneCache], list[Played]]
"""Plays one episode's items (:func:`by_episode`) with a scene cache."""


def group_player(
    config: EvalConfig,
    agent_factory: AgentFactory | None = None,
    oracle_factory: OracleFactory | None = None,
    sweep: bool = True,
) -> GroupPlayer:
    """What one episode's items come to: their records, or a refusal per budget."""
    if agent_factory is None:
        agent_factory = partial(make_agent, options=config.agent_options)
    if oracle_factory is None:
        oracle_factory = config.oracle_settings().make
    task = TaskType.parse(config.task)
    agents, oracles = agent_factory, oracle_factory

    def play(group: list[WorkItem], scenes: SceneCache) -> list[Played]:
        try:
            return list(_play_group(group, config, task, scenes, agents, oracles, sweep))
        except EpisodeRefusedError as refused:
            return [Refusal(*item.key(config), refused.reason) for item in group]

    return play


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
    seed = episode_seed(config.seed, "agent", episode)
    agent = agent_factory(config.agent, seed, config.detector)
    task_config = TaskConfig(task=task, max_steps=config.max_steps, dialog_budget=max(budgets))
    oracle = None
    if task_config.dialog_enabled:
        oracle = oracle_factory(episode_seed(config.seed, "oracle", episode))
    oracle_copies = oracle is None or getattr(oracle, "snapshottable", False)
    if not (sweep and oracle_copies and can_sweep(agent, budgets)):
        return [
            _play_item(item, config, task, scenes, agent_factory, oracle_factory) for item in group
        ]
    env = NavigationEnv([episode], task_config, scenes, oracle, privileged=agent.privileged)
    records = play_sweep(env, agent, config.agent, budgets)
    return [replace(records[budget], detector=config.detector) for budget in budgets]


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
        return episode_seed(config.seed, role, episode)

    agent = agent_factory(config.agent, seed_for("agent"), config.detector)
    task_config = TaskConfig(task=task, max_steps=config.max_steps, dialog_budget=item.budget)
    oracle = oracle_factory(seed_for("oracle")) if task_config.dialog_enabled else None
    env = NavigationEnv([episode], task_config, scenes, oracle, privileged=agent.privileged)
    return replace(play_episode(env, agent, config.agent), detector=config.detector)
