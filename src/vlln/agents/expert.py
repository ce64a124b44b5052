"""The expert: the shortest-path follower's action, an upper bound for every other agent."""

from __future__ import annotations

from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.spec import AgentOutput


class ExpertAgent:
    """Plays ``observation["expert_action"]``; it needs a privileged environment."""

    name = "expert"
    privileged = True
    snapshottable = True  # see vlln.eval.sweep

    def __init__(self, seed: int = 0) -> None:
        self.seed = int(seed)  # unused: the expert is deterministic

    def reset(self, episode: EpisodeInfo) -> None:
        return None

    def act(self, observation: Observation) -> AgentOutput:
        action = observation.get("expert_action")
        if not isinstance(action, Action):
            raise ConfigError(
                "the expert needs observation['expert_action']; run it in "
                "NavigationEnv(privileged=True)"
            )
        return action
