"""Pixel goals: where on a frame's look-down image the agent will stand a few steps later.

The reference's model moves by naming a pixel on the 30°-down image; a follower then walks
there. At frame ``t`` whose action is MOVE_FORWARD, the goal is the later frame ``t + j``
(``1 <= j <= MAX_GOAL_STEPS``) with the largest ``j`` such that

* the agent reached it by a forward step and stands somewhere else than at ``t``,
* no question is asked between ``t`` and it (it is at most the next question's frame),
* the floor point under its feet shows on frame ``t``'s look-down image: in front of the
  camera, inside the image, and what the image shows there (the rendered depth at the pixel
  matches the projected depth within ``DEPTH_TOLERANCE``, so a point hidden by furniture is
  never a goal).

* the environment's waypoint follower, sent to that pixel (:func:`vlln.tasks.waypoint.
  waypoint_for_pixel`), makes the teacher's moves from ``t`` to it and stops there
  (:class:`FollowerWalks`).

Frames that turn or stop, and forward frames where no later position shows (the look-down
camera sees the floor from about 0.67 m ahead), have no goal. The goal is computed during the
build, while the depth image is in memory, and stored with the frame.

The last rule is not the reference's. Without it a model that names the goal is walked by the
follower on its own path (it may turn first where the teacher stepped forward), so the frames
it sees next, and its history, match no training prompt; a model that fits its teacher then
fails in closed-loop play.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from vlln.datagen.collector.visibility import DOWN_TILT
from vlln.datagen.trajectory import Trajectory
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.follower import ForwardProbes
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.tasks.waypoint import waypoint_for_pixel

MAX_GOAL_STEPS = 8  # the reference's follower walks at most 8 steps per pixel goal
DEPTH_TOLERANCE = 0.1  # metres between the rendered and the projected depth of the goal
_SAME_POSITION_M = 1e-6
# Rounding to the nearest pixel centre sends halves up; a point straight ahead projects onto
# column (width - 1) / 2 + float noise, and this margin keeps the noise from deciding.
_HALF_UP_MARGIN = 1e-6


class Goal(NamedTuple):
    frames_ahead: int  # -1: no goal
    pixel: tuple[int, int]  # (column, row) on the look-down image; (-1, -1): no goal


NO_GOAL = Goal(-1, (-1, -1))


def visible_pixel(
    spec: CameraSpec,
    view: NDArray[np.float64],
    depth_image: NDArray[np.float32],
    point: NDArray[np.float64],
) -> tuple[int, int] | None:
    """The pixel (nearest centre, halves up) showing world ``point`` to the camera with
    world-to-camera matrix ``view``, or None if behind, outside or hidden."""
    local = view[:3, :3] @ point + view[:3, 3]
    depth = -float(local[2])
    if depth <= spec.near:
        return None
    fx, fy, cx, cy = spec.intrinsics()
    column = math.floor(cx + fx * float(local[0]) / depth + 0.5 + _HALF_UP_MARGIN)
    row = math.floor(cy - fy * float(local[1]) / depth + 0.5 + _HALF_UP_MARGIN)
    if not (0 <= column < spec.width and 0 <= row < spec.height):
        return None
    if abs(float(depth_image[row, column]) - depth) > DEPTH_TOLERANCE:
        return None
    return column, row


WalkCheck = Callable[[int, int, tuple[int, int], Frame], bool]
"""``(frame, later, pixel, down)``: whether a goal at ``pixel`` of frame ``frame``'s look-down
view ``down`` leads the agent along the teacher's steps to frame ``later``."""


class FollowerWalks:
    """The :data:`WalkCheck` of the environment's waypoint follower on a trajectory's house."""

    def __init__(self, sim: Simulator, trajectory: Trajectory) -> None:
        self.sim = sim
        self.steps = trajectory.steps
        # Every goal's follower is asked about the same teacher states: they share the moves.
        self.probes = ForwardProbes(sim.nav, sim.config.motion)

    def __call__(self, frame: int, later: int, pixel: tuple[int, int], down: Frame) -> bool:
        position, yaw = self.steps[frame].state.position, self.steps[frame].state.yaw
        state = AgentState(position, yaw, DOWN_TILT)
        found = waypoint_for_pixel(self.sim, down, *pixel, state, self.probes)
        if isinstance(found, str):
            return False
        taught = [step.action for step in self.steps[frame:later]] + [None]
        # Stops at the first move the follower would not make.
        return all(
            found.next_action(step.state) == action
            for step, action in zip(self.steps[frame : later + 1], taught, strict=True)
        )


class GoalFinder:
    """The goals of one trajectory, frame by frame, given each frame's look-down view.

    ``walks`` is the follower check (:class:`FollowerWalks`); None leaves it out, for
    trajectories made without a house.
    """

    def __init__(
        self, spec: CameraSpec, trajectory: Trajectory, walks: WalkCheck | None = None
    ) -> None:
        self.spec = spec
        self.steps = trajectory.steps
        self.walks = walks
        self.feet = np.array([step.state.position for step in self.steps], np.float64)
        self.question_frames = sorted({turn.frame_index for turn in trajectory.dialog})

    def at(self, frame: int, down: Frame) -> Goal:
        state = self.steps[frame].state
        if self.steps[frame].action != Action.MOVE_FORWARD:
            return NO_GOAL
        last = len(self.steps) - 1
        limit = next((f for f in self.question_frames if f > frame), last)
        view = self.spec.view_matrix(state.position, state.yaw, DOWN_TILT)
        for later in range(min(frame + MAX_GOAL_STEPS, limit), frame, -1):
            arrived = self.steps[later - 1].action == Action.MOVE_FORWARD
            moved = float(np.linalg.norm(self.feet[later] - self.feet[frame])) > _SAME_POSITION_M
            if arrived and moved:
                pixel = visible_pixel(self.spec, view, down.depth, self.feet[later])
                if pixel is not None and (
                    self.walks is None or self.walks(frame, later, pixel, down)
                ):
                    return Goal(later - frame, pixel)
        return NO_GOAL
