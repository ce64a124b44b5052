"""One training sample per decision: the images it shows and the turns of its conversation.

The human turns carry the ``<image>`` tags; the sample's image list holds one entry per tag,
in the order the tags appear: history frames, the previous look-down image, the current view
and, after ``<move>↓``, the look-down image of the current frame.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from vlln.datagen.sft import prompts
from vlln.datagen.sft.decisions import Decision, ForwardStep, PixelGoal, Stop, TurnRun
from vlln.datagen.sft.dialog import DialogExchange
from vlln.datagen.sft.history import history_frames

LEVEL = "level"  # the camera of the history and current views
DOWN = "down"  # the look-down camera


@dataclass(frozen=True)
class ImageRef:
    camera: str  # LEVEL or DOWN
    frame: int


@dataclass(frozen=True)
class Turn:
    speaker: str  # "human" or "gpt"
    value: str


@dataclass(frozen=True)
class Sample:
    frame: int
    images: tuple[ImageRef, ...]
    turns: tuple[Turn, ...]


def build_samples(
    category: str,
    decisions: Sequence[Decision],
    exchanges: Sequence[DialogExchange],
    history_count: int,
) -> list[Sample]:
    """The samples of one trajectory, one per decision, in order; ``exchanges`` are all of
    its questions as heard (budget applied), for the dialog history of later decisions."""
    dialog_frames = [exchange.frame for exchange in exchanges]
    samples: list[Sample] = []
    previous_look_down: int | None = None
    for decision in decisions:
        frame = decision.frame
        history = history_frames(frame, dialog_frames, history_count)
        heard = [(e.question, e.answer) for e in exchanges if e.frame < frame]
        images = [ImageRef(LEVEL, f) for f in history]
        if previous_look_down is not None:
            images.append(ImageRef(DOWN, previous_look_down))
        images.append(ImageRef(LEVEL, frame))
        prompt = prompts.task_prompt(category, len(history), heard, previous_look_down is not None)
        turns = [Turn("human", prompt)]
        for talk in decision.talks:
            turns += [Turn("gpt", prompts.talk_output(talk.question)), Turn("human", talk.answer)]
        move = decision.move
        if isinstance(move, PixelGoal):
            images.append(ImageRef(DOWN, frame))
            turns += [
                Turn("gpt", prompts.TILT_DOWN_OUTPUT),
                Turn("human", prompts.LOOK_DOWN_PROMPT),
                Turn("gpt", prompts.pixel_output(move.u, move.v)),
            ]
            previous_look_down = frame
        else:
            turns.append(Turn("gpt", _plain_output(move)))
        samples.append(Sample(frame, tuple(images), tuple(turns)))
    return samples


def _plain_output(move: TurnRun | ForwardStep | Stop) -> str:
    if isinstance(move, TurnRun):
        return prompts.turn_output(move.action, move.count)
    if isinstance(move, ForwardStep):
        return prompts.FORWARD_OUTPUT
    return prompts.STOP_OUTPUT
