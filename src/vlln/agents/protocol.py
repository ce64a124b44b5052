"""The one interface every agent implements (habitat-lab's ``reset``/``act``)."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.record import ModelCall, StopReason
from vlln.tasks.spec import AgentOutput


class Agent(Protocol):
    """An agent acts on observations; ``privileged`` agents also get the instance-id image,
    the ground-truth detector's lookup and the expert's next action in their observations."""

    name: str
    privileged: bool

    def reset(self, episode: EpisodeInfo) -> None: ...

    def act(self, observation: Observation) -> AgentOutput: ...


@runtime_checkable
class RecordsModelCalls(Protocol):
    """An agent that asks a model; its calls of the episode go into the episode record."""

    def model_calls(self) -> list[ModelCall]: ...


@runtime_checkable
class ReportsStopReason(Protocol):
    """An agent that says why it chose STOP; the reason goes into the episode record, where
    the failure taxonomy reads it (a stop with nothing left to explore is an exploration
    failure, not a detection failure)."""

    def stop_reason(self) -> StopReason | None: ...


def reported_stop_reason(agent: object) -> StopReason | None:
    """Why ``agent`` stopped, if it is an agent that says so."""
    return agent.stop_reason() if isinstance(agent, ReportsStopReason) else None
