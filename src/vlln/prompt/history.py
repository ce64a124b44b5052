"""Which past frames the model sees, and the dialog blocks placed after them.

History at level frame ``t`` (none at frame 0) is ``np.linspace(0, t-1, 8, dtype=int)``
without repeats, plus every earlier frame at which a question was asked, in frame order.
Each history ``<image>`` is followed by ``\\n``; a frame with questions gets, right after that,
one block holding all of its exchanges in the order they were asked::

    <image>\\n<|dialog_start|><|navigator|>q1<|oracle|>a1<|navigator|>q2<|oracle|>a2<|dialog_end|>
"""

from __future__ import annotations

import operator
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from vlln.errors import ConfigError
from vlln.prompt.outputs import question_problem, reserved_marker_in
from vlln.prompt.text import (
    DIALOG_END,
    DIALOG_START,
    IMAGE_TAG,
    NAVIGATOR,
    ORACLE,
    QUESTION_LIMIT_ANSWER,
)

DEFAULT_HISTORY_COUNT = 8


@dataclass(frozen=True)
class DialogExchange:
    """One question asked at level frame ``frame`` and the oracle's answer to it; the question
    follows the reader's rules for ``<talk>`` (so the model only ever sees askable ones)."""

    frame: int
    question: str
    answer: str

    def __post_init__(self) -> None:
        # A value object built per exchange of every prompt: it guards itself (pydantic: 3x cost).
        object.__setattr__(self, "frame", frame_index(self.frame))
        problem = question_problem(self.question)
        if problem is not None:
            raise ConfigError(f"invalid dialog question {self.question[:60]!r}: {problem}")
        check_dialog_text("answer", self.answer)


def check_dialog_text(name: str, value: str) -> None:
    """Refuse prompt text (question, answer, instruction) holding a marker that would forge
    a tag, an image or a dialog block in the prompt."""
    marker = reserved_marker_in(value)
    if marker is not None:
        raise ConfigError(
            f"the {name} may not contain {marker!r} (it would forge a tag in the prompt); "
            f"remove it from {value[:60]!r}"
        )


def frame_index(frame: object) -> int:
    """``frame`` as a plain int (numpy integers from parquet columns are welcome)."""
    try:
        index = operator.index(frame)  # type: ignore[arg-type]
    except TypeError:
        index = -1
    if isinstance(frame, bool) or index < 0:
        raise ConfigError(f"a frame is a non-negative integer, got {frame!r}")
    return index


def history_frames(
    frame: int, dialog_frames: Iterable[int], count: int = DEFAULT_HISTORY_COUNT
) -> list[int]:
    """The past frames shown at level frame ``frame``: ``count`` evenly spaced ones (the
    reference's linspace, repeats removed) and every dialog frame before ``frame``."""
    frame = frame_index(frame)
    if count < 1:
        raise ConfigError(f"history needs at least one frame, got count {count}")
    if frame == 0:
        return []
    spaced: list[int] = np.linspace(0, frame - 1, count, dtype=int).tolist()
    earlier = (int(f) for f in dialog_frames if 0 <= f < frame)
    return sorted(set(spaced).union(earlier))


def history_text(frames: Sequence[int], dialogs: Sequence[DialogExchange]) -> str:
    """``<image>\\n`` per history frame, each followed by the dialog block of its frame."""
    blocks: dict[int, list[str]] = {}
    for exchange in dialogs:
        blocks.setdefault(exchange.frame, []).append(
            f"{NAVIGATOR}{exchange.question}{ORACLE}{exchange.answer}"
        )
    parts: list[str] = []
    for frame in frames:
        parts.append(IMAGE_TAG + "\n")
        if frame in blocks:
            parts.append(DIALOG_START + "".join(blocks[frame]) + DIALOG_END)
    return "".join(parts)


def limit_answers(dialogs: Sequence[DialogExchange], limit: int) -> list[DialogExchange]:
    """``dialogs`` with every answer after the first ``limit`` replaced by the reference's
    question-limit answer, as its training data shows them (order: as asked)."""
    if limit < 0:
        raise ConfigError(f"a question limit is >= 0, got {limit}")
    return [
        exchange if index < limit else replace(exchange, answer=QUESTION_LIMIT_ANSWER)
        for index, exchange in enumerate(dialogs)
    ]
