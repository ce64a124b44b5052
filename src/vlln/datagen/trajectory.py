"""One collected trajectory in memory: the steps it took and the dialog asked along the way.

Frame ``i`` is what the agent saw in state ``steps[i].state``; ``steps[i].action`` is what it
then did. The last step's action is STOP. Questions take no frame: a dialog turn asked at frame
``i`` belongs between seeing frame ``i`` and acting on it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from vlln.sim.agent import Action, AgentState
from vlln.tasks.episode import Episode


@dataclass(frozen=True)
class Step:
    """The state a frame was seen in, the action then taken, and what it led to."""

    state: AgentState
    action: Action
    collided: bool
    geodesic_distance: float  # from ``state`` to the target's nearest view point


@dataclass(frozen=True)
class Exchange:
    """A question the collector asked and the oracle's answer."""

    frame_index: int  # the frame at which it was asked
    trigger: str  # "attribute", "route" or "disambiguation": why it was asked
    question: str
    answer: str
    question_type: str  # as the oracle classified the question


@dataclass
class Trajectory:
    """An episode walked by the collector, ready to be filtered and written."""

    episode: Episode
    steps: list[Step] = field(default_factory=list)
    dialog: list[Exchange] = field(default_factory=list)
    failure: str | None = None  # why the collector gave up, if it did
    target: str | None = None  # the goal walked to (ObjectNav: one of several); None: the first

    @property
    def target_key(self) -> str:
        """The instance id key of the goal walked to, as the episode names it."""
        return self.target if self.target is not None else self.episode.instruction.instance_id[0]

    @property
    def length(self) -> int:
        return len(self.steps)

    @property
    def path_length(self) -> float:
        """Metres walked (sum of the moves between consecutive states, up and down stairs
        included)."""
        total = 0.0
        for before, after in zip(self.steps, self.steps[1:], strict=False):
            (x0, y0, z0), (x1, y1, z1) = before.state.position, after.state.position
            total += ((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2) ** 0.5
        return total
