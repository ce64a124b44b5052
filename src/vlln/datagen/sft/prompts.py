"""The words of the training conversations (the paper's supplementary, "Training Prompt").

The first human turn of every sample is::

    You are an autonomous navigation assistant. Your task is to search for the <category>.
    You may either move or talk to an oracle. If you choose to move, first output TILT DOWN
    (↓), and then predict the next waypoint coordinates on the floor-view image. If the target
    is reached, output STOP. <history> <previous look-down> In front of you is <image>.

(one line, single spaces). ``<history>`` is "These are your historical observations:
<image> ... <dialog> <|navigator|> q <|oracle|> a ...</dialog>." with the dialog block only
when questions were asked before this frame, or :data:`NO_HISTORY` when there is nothing to
show; ``<previous look-down>`` is "Your previous look-down image is <image>." or
:data:`NO_PREVIOUS_LOOK_DOWN` before the first pixel goal. Every ``<image>`` stands for one
entry of the sample's image list, in order.

Outputs: ``<talk>question``; ``<move>←`` / ``<move>→`` repeated once per 30° turn; ``<move>↓``
(tilt down), answered with the look-down image and :data:`LOOK_DOWN_PROMPT`, then
``<move>u v`` (pixel column, then row); ``<move>↑`` for one forward step where no pixel goal
can be shown (see :mod:`vlln.datagen.sft.decisions`); ``<move>STOP``.
"""

from __future__ import annotations

from collections.abc import Sequence

from vlln.errors import ConfigError
from vlln.sim.agent import Action

IMAGE = "<image>"
TASK_INTRO = (
    "You are an autonomous navigation assistant. Your task is to search for the {category}. "
    "You may either move or talk to an oracle. If you choose to move, first output TILT DOWN "
    "(↓), and then predict the next waypoint coordinates on the floor-view image. If the "
    "target is reached, output STOP."
)
NO_HISTORY = "You have no historical observations yet."
NO_PREVIOUS_LOOK_DOWN = "You have no previous look-down image."
PREVIOUS_LOOK_DOWN = f"Your previous look-down image is {IMAGE}."
CURRENT_VIEW = f"In front of you is {IMAGE}."
LOOK_DOWN_PROMPT = f"You can see {IMAGE}. Locate the goal location on the floor in this image."

TILT_DOWN_OUTPUT = "<move>↓"
FORWARD_OUTPUT = "<move>↑"
STOP_OUTPUT = "<move>STOP"
TURN_ARROWS = {Action.TURN_LEFT: "←", Action.TURN_RIGHT: "→"}


def dialog_block(exchanges: Sequence[tuple[str, str]]) -> str:
    """``<dialog> <|navigator|> q <|oracle|> a</dialog>``, all earlier exchanges in one block."""
    body = "".join(
        f" <|navigator|> {question} <|oracle|> {answer}" for question, answer in exchanges
    )
    return f"<dialog>{body}</dialog>"


def history_sentence(image_count: int, dialog: Sequence[tuple[str, str]]) -> str:
    parts = [IMAGE] * image_count
    if dialog:
        parts.append(dialog_block(dialog))
    if not parts:
        return NO_HISTORY
    return "These are your historical observations: " + " ".join(parts) + "."


def task_prompt(
    category: str,
    history_images: int,
    dialog: Sequence[tuple[str, str]],
    has_previous_look_down: bool,
) -> str:
    """The first human turn; its images are the history, the previous look-down image (if
    any) and the current view, in that order."""
    previous = PREVIOUS_LOOK_DOWN if has_previous_look_down else NO_PREVIOUS_LOOK_DOWN
    history = history_sentence(history_images, dialog)
    return f"{TASK_INTRO.format(category=category)} {history} {previous} {CURRENT_VIEW}"


def talk_output(question: str) -> str:
    return f"<talk>{question}"


def turn_output(action: Action, count: int) -> str:
    if action not in TURN_ARROWS or count < 1:
        raise ConfigError(
            f"a turn output needs TURN_LEFT or TURN_RIGHT and a count >= 1, "
            f"got {action!r} x {count}"
        )
    return "<move>" + TURN_ARROWS[action] * count


def pixel_output(u: int, v: int) -> str:
    return f"<move>{u} {v}"
