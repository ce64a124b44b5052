"""Cutting a trajectory into the decisions the model is trained to make.

The walk goes frame by frame from frame 0. At a decision frame ``t``:

* every question asked at ``t`` comes first (``<talk>``, answered by the oracle);
* then the action at ``t`` decides the move:

  - STOP (the last frame): :class:`Stop`.
  - TURN_LEFT / TURN_RIGHT: :class:`TurnRun`, the run of the same turn starting at ``t``,
    at most ``max_turn_run`` long; the next decision is where the run ends.
  - MOVE_FORWARD: :class:`PixelGoal`, the later frame ``t + j`` (``1 <= j <= max_goal_steps``)
    with the largest ``j`` whose feet position differs from frame ``t``'s and shows on frame
    ``t``'s look-down image (see :mod:`vlln.datagen.sft.pixel_goals`); the follower walks
    there in ``j`` steps and the next decision is ``t + j``. Only frames the agent reached by
    a forward step count, so turns after the last forward of the window stay decisions of
    their own (a follower also reaches its goal with a forward step, not a turn).
  - Fallback, MOVE_FORWARD with no such frame (the next positions are too close to show:
    the look-down camera sees the floor from about 0.67 m ahead, or they are hidden or off
    the image): :class:`ForwardStep`, the single forward step itself (``<move>↑``), the
    smallest step there is; the next decision is ``t + 1``.

No move ever jumps over a frame where a question was asked: runs and pixel goals end at the
next such frame at the latest, so every question is asked at a decision frame, as it was
during collection.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vlln.datagen.sft.dialog import DialogExchange
from vlln.datagen.sft.pixel_goals import Pixel
from vlln.errors import DataFormatError
from vlln.sim.agent import Action

# Feet positions closer than this are the same position.
_SAME_POSITION_M = 1e-6
_WALKED_ACTIONS = (Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT)

# ``locate(t, s)``: the pixel of frame t's look-down image showing the feet at frame s.
Locate = Callable[[int, int], Pixel | None]


@dataclass(frozen=True)
class TurnRun:
    action: Action  # TURN_LEFT or TURN_RIGHT
    count: int

    @property
    def steps(self) -> int:
        return self.count


@dataclass(frozen=True)
class PixelGoal:
    u: int  # column on the look-down image
    v: int  # row
    steps: int  # frames until the agent stands on the goal


@dataclass(frozen=True)
class ForwardStep:
    @property
    def steps(self) -> int:
        return 1


@dataclass(frozen=True)
class Stop:
    @property
    def steps(self) -> int:
        return 0


Move = TurnRun | PixelGoal | ForwardStep | Stop


@dataclass(frozen=True)
class Decision:
    """What the model answers at ``frame``: the questions it asks there, then one move."""

    frame: int
    talks: tuple[DialogExchange, ...]
    move: Move

    @property
    def next_frame(self) -> int:
        return self.frame + self.move.steps


def check_actions(actions: Sequence[int]) -> None:
    """A trajectory's actions: moves and turns, ending with its only STOP."""
    if not actions or actions[-1] != Action.STOP:
        raise DataFormatError("the last action of a trajectory must be STOP (0)")
    for index, action in enumerate(actions[:-1]):
        if action not in _WALKED_ACTIONS:
            raise DataFormatError(
                f"action {action} at frame {index} is not MOVE_FORWARD, TURN_LEFT or "
                "TURN_RIGHT; only the last action may be STOP"
            )


def cut_decisions(
    actions: Sequence[int],
    feet: NDArray[np.float64],
    exchanges: Sequence[DialogExchange],
    locate: Locate,
    max_turn_run: int = 6,
    max_goal_steps: int = 8,
) -> list[Decision]:
    """The decisions of one trajectory in order (see the module docstring)."""
    check_actions(actions)
    last = len(actions) - 1
    talks: dict[int, list[DialogExchange]] = {}
    for exchange in exchanges:
        if not 0 <= exchange.frame <= last:
            raise DataFormatError(
                f"a question is asked at frame {exchange.frame}, outside frames 0..{last}"
            )
        talks.setdefault(exchange.frame, []).append(exchange)
    dialog_frames = sorted(talks)
    decisions: list[Decision] = []
    frame = 0
    while True:
        limit = next((f for f in dialog_frames if f > frame), last)
        move = _move_at(actions, feet, frame, limit, locate, max_turn_run, max_goal_steps)
        decisions.append(Decision(frame, tuple(talks.get(frame, ())), move))
        if isinstance(move, Stop):
            return decisions
        frame += move.steps


def _move_at(
    actions: Sequence[int],
    feet: NDArray[np.float64],
    frame: int,
    limit: int,
    locate: Locate,
    max_turn_run: int,
    max_goal_steps: int,
) -> Move:
    """The move decided at ``frame``; it may not carry the agent past frame ``limit``."""
    action = Action(int(actions[frame]))
    if action == Action.STOP:
        return Stop()
    if action in (Action.TURN_LEFT, Action.TURN_RIGHT):
        count = 1
        while count < max_turn_run and frame + count < limit and actions[frame + count] == action:
            count += 1
        return TurnRun(action, count)
    for later in range(min(frame + max_goal_steps, limit), frame, -1):
        arrived = actions[later - 1] == Action.MOVE_FORWARD
        moved = float(np.linalg.norm(feet[later] - feet[frame])) > _SAME_POSITION_M
        if arrived and moved:
            pixel = locate(frame, later)
            if pixel is not None:
                return PixelGoal(pixel[0], pixel[1], later - frame)
    return ForwardStep()
