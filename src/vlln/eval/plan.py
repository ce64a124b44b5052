"""What a run plans to play, kept in its ``run.json``, so that every reader (resume, ``vlln
score``, ``vlln report``) counts only the lines that belong to the run and can tell when
shards are missing.

A run is complete when it holds a line for every planned (episode, budget) pair, not when
it holds as many lines as it planned: a line for an episode or budget outside the plan (left
by an edited episode file, or pasted in) must not stand in for a planned one. A shard's plan
also records how many lines all the shards of its run plan together, so merging two shards
of three says which is missing instead of calling the sum complete.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from vlln.eval.config import EvalConfig
from vlln.eval.run_dir import PLAN_ALL_SHARDS, PLAN_EPISODES
from vlln.tasks.record import EpisodeRecord, agent_label


@dataclass(frozen=True)
class RunPlan:
    """The episodes one run (one shard of it) plays at each of its budgets."""

    episodes: frozenset[tuple[str, str]]  # (scene_id, episode_id)
    budgets: frozenset[int]
    all_shards: int  # episode lines planned by every shard of the run together
    agent: str  # the agent label (agent and detector) its lines carry
    task: str

    @staticmethod
    def of(episodes: Iterable[tuple[str, str]], config: EvalConfig, all_shards: int) -> RunPlan:
        return RunPlan(frozenset(episodes), frozenset(config.budgets), all_shards, *_run_of(config))

    @property
    def lines(self) -> int:
        return len(self.episodes) * len(self.budgets)

    def holds(self, record: EpisodeRecord) -> bool:
        """Whether ``record`` is one of the planned (episode, budget) pairs of this run."""
        return (
            self.is_own(record)
            and record.budget in self.budgets
            and (record.scene_id, record.episode_id) in self.episodes
        )

    def is_own(self, record: EpisodeRecord) -> bool:
        """Whether ``record`` was played by this run's agent (and detector) on its task: a
        line of another run must not stand in for a planned one, nor be scored beside them."""
        return (record.agent_label, record.task) == (self.agent, self.task)

    def to_json(self) -> dict[str, Any]:
        return {
            PLAN_EPISODES: [list(pair) for pair in sorted(self.episodes)],
            PLAN_ALL_SHARDS: self.all_shards,
        }

    @staticmethod
    def from_json(data: Any, config: EvalConfig) -> RunPlan | None:
        """The plan stored in run.json; None when absent (a run from before plans were kept)
        or not in this form."""
        if not isinstance(data, Mapping):
            return None
        episodes, all_shards = data.get(PLAN_EPISODES), data.get(PLAN_ALL_SHARDS)
        if not isinstance(episodes, list) or type(all_shards) is not int:
            return None
        pairs = [tuple(pair) for pair in episodes if isinstance(pair, list)]
        if len(pairs) != len(episodes) or any(
            len(pair) != 2 or not all(isinstance(part, str) for part in pair) for pair in pairs
        ):
            return None
        return RunPlan(
            frozenset((str(scene), str(episode)) for scene, episode in pairs),
            frozenset(config.budgets),
            all_shards,
            *_run_of(config),
        )


def _run_of(config: EvalConfig) -> tuple[str, str]:
    """The agent label and task that every line of the run carries."""
    return agent_label(config.agent, config.detector), config.task


def missing_shards(
    runs: Iterable[tuple[EvalConfig, RunPlan | None]],
) -> tuple[list[str], int | None]:
    """The shards (``"i/n"``) of the runs read that were not among them, and the episode
    lines those plan (None when a run.json predates plans)."""
    groups: dict[tuple[str, int], dict[int, RunPlan | None]] = {}
    for config, plan in runs:
        arguments = json.dumps(config.to_json() | {"shard": None}, sort_keys=True)
        groups.setdefault((arguments, config.shard.count), {})[config.shard.index] = plan
    missing: list[str] = []
    lines: int | None = 0
    for (_, count), given in groups.items():
        absent = [f"{index}/{count}" for index in range(count) if index not in given]
        if not absent:
            continue
        missing += absent
        plans = [plan for plan in given.values() if plan is not None]
        if lines is None or len(plans) < len(given):
            lines = None
        else:
            lines += plans[0].all_shards - sum(plan.lines for plan in plans)
    return missing, lines
