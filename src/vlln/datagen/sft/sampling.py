"""Which decisions of a trajectory become training samples: the reference's sampling.

With ``actions[t]`` the action done at frame ``t`` (the last is STOP) and ``n`` frames:

* every ``sample_step``-th frame ``t`` but the last: a pixel-goal sample where the
  frame has a goal, a turn sample where it turns, nothing where it steps forward without one
  (with ``forward_steps``, a one-step ``<move>↑`` sample there);
* the last frame: a STOP sample, ``repeats`` times;
* every frame where questions were asked: the same choice (a forward frame without a goal
  gives nothing), with those questions as ``<talk>`` turns first, ``repeats`` times;
* with ``hard_negatives`` copies, every frame but the last with a choice whose view shows a
  same-category distractor (:mod:`vlln.datagen.sft.distractors`): that choice again, with the
  questions asked there first, ``hard_negatives`` times (the teacher walked on or asked).

A turn sample turns as many times as the same turn repeats from ``t``, at most
``max_turn_run``, and never past a frame where questions were asked: an agent that made the
whole run would not stand at that frame to ask them. Trajectories shorter than 4 frames give
no samples, as in the reference.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from vlln.datagen.sft.config import SftConfig
from vlln.datagen.sft.source import SourceTrajectory
from vlln.errors import DataFormatError
from vlln.prompt import ForwardOutput, PixelOutput, StopOutput, TurnOutput
from vlln.sim.agent import Action

MIN_FRAMES = 4
Move = PixelOutput | TurnOutput | StopOutput | ForwardOutput
Kind = Literal["step", "stop", "dialog", "negative"]
_DIRECTIONS: dict[int, Literal["left", "right"]] = {
    Action.TURN_LEFT: "left",
    Action.TURN_RIGHT: "right",
}


@dataclass(frozen=True)
class SamplePlan:
    """A decision to train on: the frame, why it was picked, the move the model makes there
    (a pixel of the 640x480 look-down image for a pixel goal), how many copies, and whether
    the questions asked at the frame come first."""

    frame: int
    kind: Kind
    move: Move
    copies: int
    with_dialog: bool = False


def plan_samples(
    trajectory: SourceTrajectory,
    config: SftConfig,
    shows_distractor: Callable[[int], bool] | None = None,
) -> list[SamplePlan]:
    """The trajectory's samples in the order written: steps by frame, STOP, dialog frames,
    then (given ``shows_distractor``, asked only of frames with a choice) hard negatives."""
    actions = trajectory.actions
    n = len(actions)
    if n < MIN_FRAMES:
        return []
    plans: list[SamplePlan] = []
    for frame in range(0, n, config.sample_step):
        if frame == n - 1:
            continue  # the STOP frame has samples of its own
        move = _move(trajectory, frame, config)
        if move is not None:
            plans.append(SamplePlan(frame, "step", move, 1))
    plans.append(SamplePlan(n - 1, "stop", StopOutput(), config.repeats))
    asked = sorted({exchange.frame for exchange in trajectory.exchanges})
    for frame in asked:
        if not 0 <= frame < n:
            raise DataFormatError(f"a question is asked at frame {frame}, outside 0..{n - 1}")
        move = _move(trajectory, frame, config)
        if move is not None:
            plans.append(SamplePlan(frame, "dialog", move, config.repeats, with_dialog=True))
    if shows_distractor is not None:
        for frame in range(n - 1):
            move = _move(trajectory, frame, config)
            if move is not None and shows_distractor(frame):
                plans.append(
                    SamplePlan(frame, "negative", move, config.hard_negatives, frame in asked)
                )
    return plans


def _move(trajectory: SourceTrajectory, frame: int, config: SftConfig) -> Move | None:
    """The move the model is trained to make at ``frame``, None where the reference skips."""
    actions = trajectory.actions
    action = actions[frame]
    frames_ahead, (col, row) = trajectory.goals[frame]
    if frames_ahead >= 0 and action != Action.STOP:
        return PixelOutput(col, row)
    if action == Action.STOP:
        return StopOutput()
    if action == Action.MOVE_FORWARD:
        return ForwardOutput() if config.forward_steps else None
    if action not in _DIRECTIONS:
        raise DataFormatError(f"action {action} at frame {frame} is not a move, turn or STOP")
    asked = {exchange.frame for exchange in trajectory.exchanges}
    count = 1
    while (
        count < config.max_turn_run
        and frame + count < len(actions)
        and actions[frame + count] == action
        and frame + count not in asked
    ):
        count += 1
    return TurnOutput(_DIRECTIONS[action], count)


def imitator_reaches_stop(trajectory: SourceTrajectory, config: SftConfig) -> bool:
    """Whether an agent that makes exactly the exported decisions, and whose follower walks
    each pixel goal as the teacher walked it, gets from frame 0 to the STOP: every frame such
    an agent stands at needs a sample (the reference's sampling leaves forward frames without
    a visible goal bare; ``forward_steps`` fills them)."""
    frame = 0
    while True:
        move = _move(trajectory, frame, config)
        match move:
            case StopOutput():
                return True
            case None:
                return False
            case PixelOutput():
                frame += trajectory.goals[frame][0]
            case TurnOutput(count=count):
                frame += count
            case ForwardOutput():
                frame += 1
