"""Shared pieces of the evaluation tests: a tiny built split, a scene cache, test agents.

The split is the first house of the test split, built once per test session; runs play a few
of its episodes with a low step cap so that every test stays fast.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from vlln.agents.protocol import Agent
from vlln.agents.registry import make_agent
from vlln.eval.config import EvalConfig
from vlln.eval.runner import RunOutcome, run_evaluation
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import AgentOutput, Talk


class CountingAgent:
    """A test agent that counts its calls in the episode; subclasses say what it does."""

    name = "counting"
    privileged = False

    def __init__(self, seed: int) -> None:
        self.calls = 0

    def reset(self, episode: EpisodeInfo) -> None:
        self.calls = 0


class RaisingAgent(CountingAgent):
    """Raises inside act() on its third call."""

    name = "raising"

    def act(self, observation: Observation) -> AgentOutput:
        self.calls += 1
        if self.calls == 3:
            raise RuntimeError("depth sensor unplugged")
        return Action.TURN_LEFT


class GarbageAgent(CountingAgent):
    """Returns things that are not actions."""

    name = "garbage"

    def act(self, observation: Observation) -> AgentOutput:
        self.calls += 1
        garbage: list[Any] = ["<move>fly", None, 3.5, {"action": "STOP"}]
        return garbage[self.calls % len(garbage)]


class TalkingAgent(CountingAgent):
    """Asks where the target is at every step, then stops: every turn goes to the oracle."""

    name = "talking"

    def act(self, observation: Observation) -> AgentOutput:
        self.calls += 1
        return Talk("Where is it?") if self.calls <= 3 else Action.STOP


TEST_AGENTS: dict[str, type[CountingAgent]] = {
    agent.name: agent for agent in (RaisingAgent, GarbageAgent, TalkingAgent)
}


def agent_factory(name: str, seed: int, detector: str | None = None) -> Agent:
    """The registry's agents plus the test agents above."""
    if name in TEST_AGENTS:
        return TEST_AGENTS[name](seed)
    return make_agent(name, seed, detector)


def evaluate(
    out: Path,
    cache_dir: Path,
    scenes: SceneCache,
    stop_after: int | None = None,
    sweep: bool = True,
    **overrides: Any,
) -> RunOutcome:
    """Run a small evaluation: 4 episodes of the first test house, 40 counted steps at most."""
    values: dict[str, Any] = {
        "agent": "random",
        "task": "iign",
        "houses": 1,
        "episodes": 4,
        "budgets": (0, 1),
        "max_steps": 40,
        "preset": "small",
    }
    values.update(overrides)
    return run_evaluation(
        EvalConfig(**values),
        out,
        cache_dir=cache_dir,
        stop_after=stop_after,
        progress=False,
        agent_factory=agent_factory,
        scenes=scenes,
        sweep=sweep,
    )


def lines(run_dir: Path) -> list[str]:
    return (run_dir / "episodes.jsonl").read_text(encoding="utf-8").splitlines()


def summary(run_dir: Path) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((run_dir / "summary.json").read_text(encoding="utf-8"))
    return data
