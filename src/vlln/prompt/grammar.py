"""Reading model text into a ``ModelOutput``, and writing one back as text.

Only a leading ``<talk>`` or ``<move>`` tag is read, after stripping surrounding whitespace:

    <talk>question        a question (1..300 characters, no second tag or marker)
    <move>STOP            stop
    <move>↓               tilt the camera down
    <move>↑               one step forward (training never writes it)
    <move>←← / <move>→    1..4 identical turn arrows
    <move>col row         a pixel, only once the look-down image was shown, inside 640×480

Anything else is a ``ParseFailure`` with a short reason: never a silent STOP, never a digit
found somewhere turned into a pixel. Text longer than ``MAX_OUTPUT_CHARS`` is refused before
it is looked at, so the work per call is bounded whatever a model produces.
"""

from __future__ import annotations

import re
import unicodedata

from vlln.errors import ConfigError
from vlln.prompt.outputs import (
    MAX_TURN_RUN,
    Direction,
    ForwardOutput,
    ModelOutput,
    ParseFailure,
    PixelOutput,
    StopOutput,
    TalkOutput,
    TiltDownOutput,
    TurnOutput,
    ValidOutput,
    question_problem,
)
from vlln.prompt.text import (
    DOWN_ARROW,
    DOWN_IMAGE_SIZE,
    LEFT_ARROW,
    MOVE_TAG,
    RIGHT_ARROW,
    STOP_WORD,
    TALK_TAG,
    UP_ARROW,
)

MAX_OUTPUT_CHARS = 1024
EXCERPT_CHARS = 80

_PIXEL = re.compile(r"([0-9]{1,6})[ \t]+([0-9]{1,6})")
_SIGNED_PIXEL = re.compile(r"[-+]?[0-9]+[ \t,]+[-+]?[0-9]+")
_ARROWS: dict[str, Direction] = {LEFT_ARROW: "left", RIGHT_ARROW: "right"}
_REAL_ARROWS = frozenset((LEFT_ARROW, RIGHT_ARROW, DOWN_ARROW, UP_ARROW))
_OTHER_TAGS = (TALK_TAG, MOVE_TAG, "</talk>", "</move>")


def read_output(text: str, *, look_down: bool) -> ModelOutput:
    """The output ``text`` stands for; ``look_down`` says whether the look-down image was the
    last picture shown (only then is a pixel accepted). Never raises."""
    if len(text) > MAX_OUTPUT_CHARS:
        return _failure(f"output longer than {MAX_OUTPUT_CHARS} characters", text)
    stripped = text.strip()
    if not stripped:
        return _failure("empty output", text)
    if stripped.startswith(TALK_TAG):
        return _read_talk(stripped[len(TALK_TAG) :], text)
    if stripped.startswith(MOVE_TAG):
        return _read_move(stripped[len(MOVE_TAG) :].strip(), text, look_down)
    return _failure("no leading <talk> or <move> tag", text)


def format_output(output: ValidOutput) -> str:
    """The exact assistant text for ``output`` (what training data holds)."""
    match output:
        case TalkOutput(question=question):
            return TALK_TAG + question
        case TurnOutput(direction=direction, count=count):
            return MOVE_TAG + (LEFT_ARROW if direction == "left" else RIGHT_ARROW) * count
        case TiltDownOutput():
            return MOVE_TAG + DOWN_ARROW
        case ForwardOutput():
            return MOVE_TAG + UP_ARROW
        case PixelOutput(col=col, row=row):
            return f"{MOVE_TAG}{col} {row}"
        case StopOutput():
            return MOVE_TAG + STOP_WORD
    raise ConfigError(f"only a valid model output has a text, got {output!r}")


def _failure(reason: str, text: str) -> ParseFailure:
    return ParseFailure(reason, text[:EXCERPT_CHARS])


def _second_tag(body: str) -> bool:
    return any(tag in body for tag in _OTHER_TAGS)


def _read_talk(body: str, text: str) -> ModelOutput:
    if _second_tag(body):
        return _failure("more than one tag", text)
    question = body.strip()
    problem = question_problem(question)
    if problem is not None:
        return _failure(problem, text)
    return TalkOutput(question)


def _read_move(body: str, text: str, look_down: bool) -> ModelOutput:
    if not body:
        return _failure("empty move", text)
    if _second_tag(body):
        return _failure("more than one tag", text)
    if body == STOP_WORD:
        return StopOutput()
    if body == DOWN_ARROW:
        return TiltDownOutput()
    if body == UP_ARROW:
        return ForwardOutput()
    if body[0] in _ARROWS:
        return _read_turns(body, text)
    if body[0].isascii() and body[0].isdigit():
        return _read_pixel(body, text, look_down)
    return _failure(_unknown_move_reason(body), text)


def _read_turns(body: str, text: str) -> ModelOutput:
    chars = set(body)
    if len(chars) > 1:
        reason = "mixed turn arrows" if chars <= _ARROWS.keys() else _unknown_move_reason(body)
        return _failure(reason, text)
    if len(body) > MAX_TURN_RUN:
        return _failure(f"more than {MAX_TURN_RUN} turn arrows", text)
    return TurnOutput(_ARROWS[body[0]], len(body))


def _read_pixel(body: str, text: str, look_down: bool) -> ModelOutput:
    match = _PIXEL.fullmatch(body)
    if match is None:
        return _failure("a pixel is two integers 'col row'", text)
    if not look_down:
        return _failure("pixel without a look-down image", text)
    col, row = int(match.group(1)), int(match.group(2))
    width, height = DOWN_IMAGE_SIZE
    if col >= width or row >= height:
        return _failure(f"pixel outside the {width}x{height} look-down image", text)
    return PixelOutput(col, row)


def _unknown_move_reason(body: str) -> str:
    """The most telling reason why ``body`` is no move: lookalike arrows first."""
    for char in body:
        if "\ufe00" <= char <= "\ufe0f":
            return "variation selector in a move"
        if char not in _REAL_ARROWS and "ARROW" in unicodedata.name(char, ""):
            return f"lookalike arrow U+{ord(char):04X}; use ← or →"
    if _SIGNED_PIXEL.fullmatch(body):
        return "a pixel is two non-negative integers 'col row'"
    return "unknown move"
