"""The dialog-budget sweep by prefix sharing: every budget of one episode from one run.

An episode under budget k is the same as under the largest budget until the agent asks its
(k+1)-th question, which budget k refuses. So the sweep plays the largest budget once,
copies the environment (with its oracle) and the agent at the moment each of those questions
is asked, and continues every lower budget from its copy with the question refused. Budgets
whose question never comes get the full run's record under their own budget.

This holds for agents that set ``snapshottable = True``: ``copy.deepcopy`` of the agent is a
faithful snapshot, and its actions read the budget only through refusals (never from
``questions_left`` or ``EpisodeInfo.dialog_budget``), as the reference's agents learn it.
Other agents play each budget on its own (:func:`can_sweep`). The records are those of
independent runs, byte for byte apart from answer latencies (tested).

Copies share what does not change during an episode (the simulator, the house, its grid,
geodesic fields, the oracle's house index): the snapshot is the episode's state, not the world.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Sequence
from typing import Any

from vlln.agents.protocol import Agent, reported_stop_reason
from vlln.errors import ServerDownError
from vlln.oracle.knowledge import HouseIndex
from vlln.sim.agent import AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv, Observation
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import AgentOutput, Talk
from vlln.world.model import House

# Kept, not copied, by a snapshot: fixed for the whole episode (or shared with other episodes).
_SHARED_TYPES = (Simulator, SceneCache, House, NavGrid, GeodesicField, GreedyFollower, HouseIndex)
_SEARCH_DEPTH = 4


def describe_error(error: Exception, where: str) -> str:
    """The ``error`` field of a record that the agent's ``reset`` or ``act`` ended; a server
    given up on (:class:`ServerDownError`) is no fault of the agent's and is raised again, to
    stop the run with the episode unwritten (a rerun plays it)."""
    if isinstance(error, ServerDownError):
        raise error
    return f"{type(error).__name__} in agent.{where}(): {error}"[:2000]


def can_sweep(agent: Agent, budgets: Sequence[int]) -> bool:
    """Whether :func:`play_sweep` may play these budgets of this agent together."""
    return len(budgets) > 1 and bool(getattr(agent, "snapshottable", False))


@dataclasses.dataclass
class _Snapshot:
    env: NavigationEnv
    agent: Agent
    state: AgentState
    question: Talk


def play_sweep(
    env: NavigationEnv, agent: Agent, agent_name: str, budgets: Sequence[int]
) -> dict[int, EpisodeRecord]:
    """Records of ``env``'s first episode at each of ``budgets``; see the module doc."""
    top = max(budgets)
    lower = {budget for budget in budgets if budget < top}
    env.config = dataclasses.replace(env.config, dialog_budget=top)
    observation, _ = env.reset(options={"episode_index": 0})
    try:
        agent.reset(env.episode_info())
    except Exception as error:
        failed = env.record(agent_name, error=describe_error(error, "reset"))
        return {budget: dataclasses.replace(failed, budget=budget) for budget in budgets}
    snapshots: dict[int, _Snapshot] = {}
    while True:
        try:
            action = agent.act(observation)
        except Exception as error:
            full = env.record(agent_name, error=describe_error(error, "act"))
            break
        asked = env.questions_answered
        if isinstance(action, Talk) and asked in lower and asked not in snapshots:
            snapshots[asked] = _snapshot(env, agent, action)
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            full = env.record(agent_name, stop_reason=reported_stop_reason(agent))
            break
    records = {top: full}
    for budget in sorted(lower):
        snapshot = snapshots.get(budget)
        if snapshot is None:
            records[budget] = dataclasses.replace(full, budget=budget)
        else:
            records[budget] = _continue(snapshot, budget, agent_name)
    return {budget: records[budget] for budget in budgets}


def _snapshot(env: NavigationEnv, agent: Agent, question: Talk) -> _Snapshot:
    memo: dict[int, Any] = {}
    for root in (env, agent):
        _share(root, memo, _SEARCH_DEPTH)
    env_copy, agent_copy = copy.deepcopy((env, agent), memo)
    return _Snapshot(env_copy, agent_copy, env.sim.state, question)


def _share(value: Any, memo: dict[int, Any], depth: int) -> None:
    """Enter every shared object reachable within ``depth`` attribute hops into ``memo``."""
    if isinstance(value, _SHARED_TYPES):
        memo[id(value)] = value
        return
    if depth == 0:
        return
    children: Any
    if isinstance(value, dict):
        children = value.values()
    elif isinstance(value, list | tuple):
        children = value
    elif hasattr(value, "__dict__"):
        children = vars(value).values()
    else:
        return
    for child in children:
        _share(child, memo, depth - 1)


def _continue(snapshot: _Snapshot, budget: int, agent_name: str) -> EpisodeRecord:
    """Play on from a snapshot under ``budget``, whose refusal of the question comes first."""
    env, agent = snapshot.env, snapshot.agent
    env.config = dataclasses.replace(env.config, dialog_budget=budget)
    env.sim.reset(snapshot.state)
    action: AgentOutput = snapshot.question
    while True:
        observation: Observation
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            return env.record(agent_name, stop_reason=reported_stop_reason(agent))
        try:
            action = agent.act(observation)
        except Exception as error:
            return env.record(agent_name, error=describe_error(error, "act"))
