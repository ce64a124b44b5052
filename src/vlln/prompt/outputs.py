"""What a navigation model can answer, one type per kind of answer.

The model speaks (``TalkOutput``), turns up to 4 × 30° one way (``TurnOutput``), tilts the
camera down (``TiltDownOutput``), names a pixel of the look-down image (``PixelOutput``),
steps forward (``ForwardOutput``, accepted though training never writes it) or stops.
``ParseFailure`` is an answer that follows none of these: it costs the agent one step and is
recorded, never read as a STOP. Constructors check their values, so a valid output always
has a text (``format_output``) that reads back to itself (``read_output``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, TypeAlias

from vlln.errors import ConfigError
from vlln.prompt.text import DOWN_IMAGE_SIZE, RESERVED_MARKERS
from vlln.sim.agent import Action

MAX_QUESTION_CHARS = 300
MAX_TURN_RUN = 4

Direction: TypeAlias = Literal["left", "right"]


def reserved_marker_in(text: str) -> str | None:
    """The first reserved marker (``<image>``, ``<|``, a tag) found in ``text``, if any."""
    for marker in RESERVED_MARKERS:
        if marker in text:
            return marker
    return None


@dataclass(frozen=True)
class TalkOutput:
    """Ask the oracle ``question``: non-empty, stripped, at most 300 characters, no markers."""

    question: str

    def __post_init__(self) -> None:
        # A value object built per decision and training line: it guards itself (pydantic: 3x).
        problem = question_problem(self.question)
        if problem is not None:
            raise ConfigError(f"invalid question {self.question[:60]!r}: {problem}")


@dataclass(frozen=True)
class TurnOutput:
    """Turn ``count`` (1..4) times 30° to the ``direction`` side."""

    direction: Direction
    count: int = 1

    def __post_init__(self) -> None:
        # A value object built per decision and training line: it guards itself (pydantic: 3x).
        if self.direction not in ("left", "right"):
            raise ConfigError(f"a turn goes 'left' or 'right', got {self.direction!r}")
        if isinstance(self.count, bool) or not 1 <= self.count <= MAX_TURN_RUN:
            raise ConfigError(f"a turn run has 1 to {MAX_TURN_RUN} turns, got {self.count!r}")

    @property
    def action(self) -> Action:
        return Action.TURN_LEFT if self.direction == "left" else Action.TURN_RIGHT


@dataclass(frozen=True)
class TiltDownOutput:
    """Tilt the camera 30° down to be shown the look-down image."""


@dataclass(frozen=True)
class ForwardOutput:
    """One 0.25 m step forward (``<move>↑``)."""


@dataclass(frozen=True)
class StopOutput:
    """Declare the target reached."""


@dataclass(frozen=True)
class PixelOutput:
    """Walk towards pixel (``col``, ``row``) of the 640×480 look-down image."""

    col: int
    row: int

    def __post_init__(self) -> None:
        # A value object built per decision and training line: it guards itself (pydantic: 3x).
        width, height = DOWN_IMAGE_SIZE
        for name, value, size in (("col", self.col, width), ("row", self.row, height)):
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value < size:
                raise ConfigError(f"pixel {name} must be an integer in [0, {size}), got {value!r}")


@dataclass(frozen=True)
class ParseFailure:
    """Model text that is no valid output: ``reason`` says why, ``text`` is its start."""

    reason: str
    text: str


ValidOutput: TypeAlias = (
    TalkOutput | TurnOutput | TiltDownOutput | ForwardOutput | PixelOutput | StopOutput
)
ModelOutput: TypeAlias = ValidOutput | ParseFailure


def question_problem(question: str) -> str | None:
    """Why ``question`` cannot be asked, or None when it can."""
    if not question:
        return "empty question"
    if question != question.strip():
        return "question has surrounding whitespace"
    if len(question) > MAX_QUESTION_CHARS:
        return f"question longer than {MAX_QUESTION_CHARS} characters"
    marker = reserved_marker_in(question)
    if marker is not None:
        return f"question contains the reserved marker {marker!r}"
    return None
