"""A built trajectory played again through the evaluation environment, as an agent.

A model trained on a dataset imitates its teacher, the collector; the teacher's score on the
same episodes, measured by the same runner and metrics as the model's, is the bar an imitation
is held to (``vlln bench learning``). The replay asks the trajectory's questions at the frames
they were asked and then makes the recorded moves, one per step.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable

from vlln.datagen.sft.source import SourceTrajectory
from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.spec import AgentOutput, Talk


class TrajectoryReplay:
    """Plays the recorded trajectory of each episode it is reset to."""

    name = "teacher"
    privileged = False

    def __init__(self, trajectories: Iterable[SourceTrajectory]) -> None:
        self._by_episode = {trajectory.episode_key: trajectory for trajectory in trajectories}
        self._plan: deque[AgentOutput] = deque()

    def reset(self, episode: EpisodeInfo) -> None:
        trajectory = self._by_episode.get(episode.episode_id)
        if trajectory is None:
            raise ConfigError(f"no recorded trajectory for episode {episode.episode_id!r}")
        questions: dict[int, list[str]] = {}
        for exchange in trajectory.exchanges:
            questions.setdefault(exchange.frame, []).append(exchange.question)
        plan: deque[AgentOutput] = deque()
        for frame, action in enumerate(trajectory.actions):
            plan.extend(Talk(question) for question in questions.get(frame, []))
            plan.append(Action(action))
        self._plan = plan

    def act(self, observation: Observation) -> AgentOutput:
        return self._plan.popleft() if self._plan else Action.STOP
