"""The one interface every agent implements (habitat-lab's ``reset``/``act``)."""

from __future__ import annotations

from typing import Protocol

from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.spec import AgentOutput


class Agent(Protocol):
    """An agent acts on observations; ``privileged`` agents also get the instance-id image,
    the ground-truth detector's lookup and the expert's next action in their observations."""

    name: str
    privileged: bool

    def reset(self, episode: EpisodeInfo) -> None: ...

    def act(self, observation: Observation) -> AgentOutput: ...
