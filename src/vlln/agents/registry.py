"""Agents by name, for the command line and the evaluation runner."""

from __future__ import annotations

from collections.abc import Callable

from vlln.agents.expert import ExpertAgent
from vlln.agents.frontier import FrontierAgent
from vlln.agents.protocol import Agent
from vlln.agents.random_agent import RandomAgent
from vlln.errors import ConfigError

AGENTS: dict[str, Callable[[int], Agent]] = {
    "random": RandomAgent,
    "expert": ExpertAgent,
    "frontier": FrontierAgent,
}


def make_agent(name: str, seed: int) -> Agent:
    """A fresh agent of the named kind, seeded."""
    factory = AGENTS.get(name)
    if factory is None:
        raise ConfigError(f"unknown agent {name!r}; choose one of: {', '.join(sorted(AGENTS))}")
    return factory(seed)
