"""The two views stored for each frame of a kept trajectory, with one render per frame.

The collector renders the level view of every step to decide its next action (its frames are
level: it never tilts the camera). Rendering that view again for a kept trajectory would
double the build's most expensive work, so :class:`LevelViews` stores each one as it is
collected, already encoded as the data set's JPEG: about 10 kB a frame, so even a 500-step
trajectory holds about 5 MB, where its raw frames would take 460 MB. Only the look-down view
is rendered for a kept trajectory (:func:`down_views`). Encoding the frames of trajectories
that are then dropped costs far less than the renders it saves (a frame encodes in about a
tenth of the time it renders).
"""

from __future__ import annotations

from collections.abc import Iterator

from vlln.datagen.collector.visibility import DOWN_TILT
from vlln.datagen.trajectory import Trajectory
from vlln.prompt.images import stored_frame
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator


class LevelViews:
    """The stored level view of every collected step (pass :meth:`keep` to the collector)."""

    def __init__(self) -> None:
        self.stored: list[bytes] = []
        self._last: Frame | None = None

    def keep(self, frame: Frame) -> None:
        self.stored.append(stored_frame(frame.rgb))
        self._last = frame

    @property
    def last(self) -> Frame:
        """The last step's level view, which the final-view filter looks at."""
        if self._last is None:
            raise ValueError("no step has been collected")
        return self._last


def down_views(sim: Simulator, trajectory: Trajectory, last: Frame) -> Iterator[Frame]:
    """The 30°-down view of every step, rendered from the recorded states; the last step's is
    ``last``, which the final-view filter has had rendered already (:func:`final_down_view`)."""
    for step in trajectory.steps[:-1]:
        state = step.state
        yield sim.render(AgentState(state.position, state.yaw, DOWN_TILT))
    yield last


def final_down_view(sim: Simulator, trajectory: Trajectory) -> Frame:
    """The 30°-down view of the trajectory's last step."""
    state = trajectory.steps[-1].state
    return sim.render(AgentState(state.position, state.yaw, DOWN_TILT))
