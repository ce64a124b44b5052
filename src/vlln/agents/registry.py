"""Agents by name, for the command line and the evaluation runner: the built-in ones, and
any class that implements the protocol, named ``package.module:Class``."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from vlln.agents.aiuta.options import AiutaOptions, aiuta_agent
from vlln.agents.custom import is_agent_spec, load_agent
from vlln.agents.expert import ExpertAgent
from vlln.agents.frontier import FrontierAgent, FrontierConfig
from vlln.agents.frontier.options import FrontierOptions, frontier_agent
from vlln.agents.frontier.perception import check_detector
from vlln.agents.local.options import VllnOptions, vlln_agent
from vlln.agents.model.options import OpenAIVLMOptions, openai_vlm_agent
from vlln.agents.options import AgentOptions
from vlln.agents.protocol import Agent
from vlln.agents.random_agent import RandomAgent
from vlln.agents.vlfm.agent import VlfmAgent
from vlln.errors import ConfigError


def fbe_agent(seed: int, detector: str = "truth") -> FrontierAgent:
    """The paper's FBE baseline: the frontier agent that never asks the oracle."""
    return FrontierAgent(seed, FrontierConfig(asks=False), detector=detector)


def comparing_agent(seed: int, detector: str = "truth") -> FrontierAgent:
    """The frontier agent that asks which candidate is meant when several are in view and
    reads the helpful oracle's clarifications (docs/helpful-oracle.md)."""
    return FrontierAgent(seed, FrontierConfig(compares=True), detector=detector)


AGENTS: dict[str, Callable[[int], Agent]] = {
    "random": RandomAgent,
    "expert": ExpertAgent,
    "frontier": FrontierAgent,
    "frontier-compare": comparing_agent,
    "fbe": fbe_agent,
    "vlfm": VlfmAgent,
}

OPTIONS: dict[str, type[AgentOptions]] = {
    "openai-vlm": OpenAIVLMOptions,
    "vlln": VllnOptions,
    "aiuta": AiutaOptions,
    "frontier": FrontierOptions,
}
"""The options class of each agent that takes options (which server, which model); stored in
run.json. Every other agent takes none (:class:`AgentOptions` itself, empty)."""

CONFIGURED_AGENTS: dict[str, Callable[[int, Any], Agent]] = {
    "openai-vlm": openai_vlm_agent,
    "vlln": vlln_agent,
}

CONFIGURED_DETECTING_AGENTS: dict[str, Callable[[int, Any, str], Agent]] = {
    "aiuta": aiuta_agent,
    "frontier": frontier_agent,
}
"""Agents that take options and perceive objects through a detector."""

DETECTING_AGENTS: dict[str, Callable[[int, str], Agent]] = {
    "frontier-compare": comparing_agent,
    "fbe": fbe_agent,
    "vlfm": lambda seed, detector: VlfmAgent(seed, detector=detector),
}
"""Agents that perceive objects through a detector (``vlln.agents.frontier.perception``)."""
DEFAULT_DETECTOR = "truth"


def resolve_detector(agent: str, detector: str | None) -> str | None:
    """The detector ``agent`` runs with: ``detector``, checked, or the ground-truth one; None
    for agents without one (naming a detector for those is an error)."""
    if agent not in DETECTING_AGENTS and agent not in CONFIGURED_DETECTING_AGENTS:
        if detector is not None:
            raise ConfigError(
                f"agent {agent!r} uses no detector; --detector applies to: "
                + ", ".join(sorted([*DETECTING_AGENTS, *CONFIGURED_DETECTING_AGENTS]))
            )
        return None
    return check_detector(detector or DEFAULT_DETECTOR)


def agent_options(name: str, values: AgentOptions | Mapping[str, Any] | None) -> AgentOptions:
    """The options of agent ``name``: ``values`` (keyed by option or flag name, strings
    converted) checked against the agent's class; an option for an agent without any, an
    unknown one or a bad value is one :class:`ConfigError` line."""
    options = OPTIONS.get(name, AgentOptions)
    if isinstance(values, AgentOptions):
        if type(values) is options:
            return values
        values = values.to_json()
    return options.parse(name, values or {})


def make_agent(
    name: str,
    seed: int,
    detector: str | None = None,
    options: AgentOptions | Mapping[str, Any] | None = None,
) -> Agent:
    """A fresh agent of the named kind, seeded; ``detector`` for agents that perceive through
    one, ``options`` only for agents that take them."""
    configured = CONFIGURED_AGENTS.get(name)
    if configured is not None:
        resolve_detector(name, detector)
        return configured(seed, agent_options(name, options))
    sighted = CONFIGURED_DETECTING_AGENTS.get(name)
    if sighted is not None:
        sight = resolve_detector(name, detector) or DEFAULT_DETECTOR
        return sighted(seed, agent_options(name, options), sight)
    if name not in AGENTS and not is_agent_spec(name):
        names = ", ".join(sorted({*AGENTS, *CONFIGURED_AGENTS, *CONFIGURED_DETECTING_AGENTS}))
        raise ConfigError(
            f"unknown agent {name!r}; choose one of: {names}, or name a class of your own as "
            "package.module:Class (docs/own-agent.md)"
        )
    agent_options(name, options)  # refuses options given to an agent without any
    chosen = resolve_detector(name, detector)
    if is_agent_spec(name):
        return load_agent(name, seed)
    if chosen is None:
        return AGENTS[name](seed)
    return DETECTING_AGENTS[name](seed, chosen)
