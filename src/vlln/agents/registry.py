"""Agents by name, for the command line and the evaluation runner."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from vlln.agents.expert import ExpertAgent
from vlln.agents.frontier import FrontierAgent
from vlln.agents.local.options import vlln_agent
from vlln.agents.model.options import openai_vlm_agent
from vlln.agents.protocol import Agent
from vlln.agents.random_agent import RandomAgent
from vlln.errors import ConfigError

AGENTS: dict[str, Callable[[int], Agent]] = {
    "random": RandomAgent,
    "expert": ExpertAgent,
    "frontier": FrontierAgent,
}

# Agents that take options (which server, which model), stored in run.json.
CONFIGURED_AGENTS: dict[str, Callable[[int, Mapping[str, str]], Agent]] = {
    "openai-vlm": openai_vlm_agent,
    "vlln": vlln_agent,
}


def make_agent(name: str, seed: int, options: Mapping[str, str] | None = None) -> Agent:
    """A fresh agent of the named kind, seeded; ``options`` only for agents that take them."""
    options = options or {}
    configured = CONFIGURED_AGENTS.get(name)
    if configured is not None:
        return configured(seed, options)
    factory = AGENTS.get(name)
    if factory is None:
        names = ", ".join(sorted([*AGENTS, *CONFIGURED_AGENTS]))
        raise ConfigError(f"unknown agent {name!r}; choose one of: {names}")
    if options:
        raise ConfigError(f"agent {name!r} takes no options, got {', '.join(sorted(options))}")
    return factory(seed)
