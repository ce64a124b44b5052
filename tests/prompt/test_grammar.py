"""The output reader: a table of model texts and what they mean, and the text round trip."""

from __future__ import annotations

import random

import pytest

from vlln.errors import ConfigError
from vlln.prompt import (
    MAX_OUTPUT_CHARS,
    ForwardOutput,
    ModelOutput,
    ParseFailure,
    PixelOutput,
    StopOutput,
    TalkOutput,
    TiltDownOutput,
    TurnOutput,
    ValidOutput,
    format_output,
    read_output,
)

WELL_FORMED: list[tuple[str, bool, ModelOutput]] = [
    ("<move>STOP", False, StopOutput()),
    ("<move>STOP", True, StopOutput()),
    ("  <move>STOP\n", False, StopOutput()),
    ("<move> STOP", False, StopOutput()),
    ("<move>↓", False, TiltDownOutput()),
    ("<move>↑", False, ForwardOutput()),
    ("<move>←", False, TurnOutput("left", 1)),
    ("<move>←←", False, TurnOutput("left", 2)),
    ("<move>→→→", False, TurnOutput("right", 3)),
    ("<move>→→→→", True, TurnOutput("right", 4)),
    ("<move>320 240", True, PixelOutput(320, 240)),
    ("<move>0 0", True, PixelOutput(0, 0)),
    ("<move>639 479", True, PixelOutput(639, 479)),
    ("<move>007 12", True, PixelOutput(7, 12)),
    ("<move>12\t30", True, PixelOutput(12, 30)),
    ("<talk>Is the chair in the bedroom?", False, TalkOutput("Is the chair in the bedroom?")),
    ("<talk> Which way now? \n", True, TalkOutput("Which way now?")),
    ("<talk>Is it 3 m away, near door 2?", False, TalkOutput("Is it 3 m away, near door 2?")),
    ("<talk>STOP", False, TalkOutput("STOP")),
    ("<talk>" + "q" * 300, False, TalkOutput("q" * 300)),
]

MALFORMED: list[tuple[str, bool, str]] = [
    ("", False, "empty output"),
    ("   \n\t ", False, "empty output"),
    ("STOP", False, "no leading <talk> or <move> tag"),
    ("Sure! <move>STOP", False, "no leading <talk> or <move> tag"),
    ("<Move>STOP", False, "no leading <talk> or <move> tag"),
    ("320 240", True, "no leading <talk> or <move> tag"),
    ("<move>", False, "empty move"),
    ("<move>   ", False, "empty move"),
    ("<move>stop", False, "unknown move"),
    ("<move>STOP now", False, "unknown move"),
    ("<move>↓↓", False, "unknown move"),
    ("<move>↑↑", False, "unknown move"),
    ("<move>←→", False, "mixed turn arrows"),
    ("<move>←←←←←", False, "more than 4 turn arrows"),
    ("<move>← ←", False, "unknown move"),
    ("<move>⬅", False, "lookalike arrow U+2B05; use ← or →"),
    ("<move>⇐", False, "lookalike arrow U+21D0; use ← or →"),
    ("<move>⟵", False, "lookalike arrow U+27F5; use ← or →"),
    ("<move>↩", False, "lookalike arrow U+21A9; use ← or →"),
    ("<move>➡", False, "lookalike arrow U+27A1; use ← or →"),
    ("<move>←\ufe0f", False, "variation selector in a move"),
    ("<move>⬅️", False, "lookalike arrow U+2B05; use ← or →"),
    ("<move>320 240", False, "pixel without a look-down image"),
    ("<move>640 240", True, "pixel outside the 640x480 look-down image"),
    ("<move>320 480", True, "pixel outside the 640x480 look-down image"),
    ("<move>9999999 1", True, "a pixel is two integers 'col row'"),
    ("<move>320", True, "a pixel is two integers 'col row'"),
    ("<move>320 240 5", True, "a pixel is two integers 'col row'"),
    ("<move>320,240", True, "a pixel is two integers 'col row'"),
    ("<move>3.5 2", True, "a pixel is two integers 'col row'"),
    ("<move>-3 240", True, "a pixel is two non-negative integers 'col row'"),
    ("<move>(320, 240)", True, "unknown move"),
    ("<move>٣٢ ٤", True, "unknown move"),  # Arabic-Indic digits are not ASCII digits
    ("<move>３２０ ２４０", True, "unknown move"),  # full-width digits
    ("<move>STOP<move>STOP", False, "more than one tag"),
    ("<move>←<talk>where?", False, "more than one tag"),
    ("<talk>where?<move>STOP", False, "more than one tag"),
    ("<talk>where?</talk>", False, "more than one tag"),
    ("<talk><talk>where?", False, "more than one tag"),
    ("<talk>", False, "empty question"),
    ("<talk>   ", False, "empty question"),
    ("<talk>" + "q" * 301, False, "question longer than 300 characters"),
    ("<talk>Is it <image> here?", False, "question contains the reserved marker '<image>'"),
    ("<talk>ok<|oracle|>yes", False, "question contains the reserved marker '<|'"),
    ("<talk>a|>b", False, "question contains the reserved marker '|>'"),
    ("x" * (MAX_OUTPUT_CHARS + 1), False, f"output longer than {MAX_OUTPUT_CHARS} characters"),
    ("<move>STOP" + " " * 10_000, False, f"output longer than {MAX_OUTPUT_CHARS} characters"),
    ("<talk>" + "where? " * 1500, False, f"output longer than {MAX_OUTPUT_CHARS} characters"),
    ("<move>" + "←" * 1000, False, "more than 4 turn arrows"),
    ("<move>" + "⬅" * 1000, False, "lookalike arrow U+2B05; use ← or →"),
    ("<move>" + "7" * 1000, True, "a pixel is two integers 'col row'"),
]


@pytest.mark.parametrize(("text", "look_down", "expected"), WELL_FORMED)
def test_well_formed_outputs_are_read(text: str, look_down: bool, expected: ModelOutput) -> None:
    assert read_output(text, look_down=look_down) == expected


@pytest.mark.parametrize(("text", "look_down", "reason"), MALFORMED)
def test_malformed_outputs_are_failures_with_a_reason(
    text: str, look_down: bool, reason: str
) -> None:
    result = read_output(text, look_down=look_down)
    assert result == ParseFailure(reason, text[:80])


def test_ten_kilobytes_of_arbitrary_text_never_raise_nor_stop() -> None:
    rng = random.Random(7)
    alphabet = "<>/movetalkSTOP←→↑↓⬅️ 0123456789\n\t|image"
    for length in (0, 1, 5, 40, 300, 1024, 1025, 10_240):
        for _ in range(20):
            text = "".join(rng.choice(alphabet) for _ in range(length))
            for look_down in (False, True):
                result = read_output(text, look_down=look_down)
                if not isinstance(result, ParseFailure):
                    assert read_output(format_output(result), look_down=True) == result
                    assert text.strip().startswith(("<talk>", "<move>"))
                else:
                    assert len(result.text) <= 80


def all_valid_outputs() -> list[ValidOutput]:
    rng = random.Random(3)
    outputs: list[ValidOutput] = [StopOutput(), TiltDownOutput(), ForwardOutput()]
    outputs += [TurnOutput(d, n) for d in ("left", "right") for n in range(1, 5)]
    outputs += [PixelOutput(c, r) for c in (0, 1, 639) for r in (0, 1, 479)]
    outputs += [PixelOutput(rng.randrange(640), rng.randrange(480)) for _ in range(200)]
    questions = ["Where is it?", "Is it 2 m to the left of door 3?", "STOP", "↓", "a" * 300]
    questions += ["Is it the red one → or the blue one ←?", "über straße? 椅子在哪里?", "a\nb"]
    outputs += [TalkOutput(q) for q in questions]
    return outputs


def random_questions(count: int) -> list[TalkOutput]:
    """Seeded questions over an alphabet of digits, arrows, tags' pieces and other scripts;
    the ones a ``TalkOutput`` refuses are left out."""
    rng = random.Random(5)
    alphabet = "ab Z09?.,<>|/←→↓↑⬅️ STOPmovetalkimage\n\té椅ا🙂\u200b"
    questions: list[TalkOutput] = []
    while len(questions) < count:
        text = "".join(rng.choice(alphabet) for _ in range(rng.randrange(1, 320)))
        try:
            questions.append(TalkOutput(text))
        except ConfigError:
            continue
    return questions


def test_reading_the_written_text_gives_the_output_back() -> None:
    for output in [*all_valid_outputs(), *random_questions(300)]:
        assert read_output(format_output(output), look_down=True) == output


def test_written_texts_are_the_reference_training_texts() -> None:
    assert format_output(StopOutput()) == "<move>STOP"
    assert format_output(TiltDownOutput()) == "<move>↓"
    assert format_output(ForwardOutput()) == "<move>↑"
    assert format_output(TurnOutput("left", 3)) == "<move>←←←"
    assert format_output(TurnOutput("right", 1)) == "<move>→"
    assert format_output(PixelOutput(12, 345)) == "<move>12 345"
    assert format_output(TalkOutput("Where?")) == "<talk>Where?"


@pytest.mark.parametrize(
    "make",
    [
        lambda: TurnOutput("left", 0),
        lambda: TurnOutput("left", 5),
        lambda: TurnOutput("up", 1),  # type: ignore[arg-type]
        lambda: PixelOutput(640, 0),
        lambda: PixelOutput(0, -1),
        lambda: TalkOutput(""),
        lambda: TalkOutput(" padded"),
        lambda: TalkOutput("x" * 301),
        lambda: TalkOutput("two <move>STOP"),
    ],
)
def test_invalid_outputs_cannot_be_made(make: object) -> None:
    with pytest.raises(ConfigError):
        make()  # type: ignore[operator]


def test_a_failure_has_no_text() -> None:
    with pytest.raises(ConfigError, match="only a valid model output"):
        format_output(ParseFailure("empty output", ""))  # type: ignore[arg-type]


def test_turn_outputs_name_their_simulator_action() -> None:
    from vlln.sim.agent import Action

    assert TurnOutput("left", 2).action is Action.TURN_LEFT
    assert TurnOutput("right", 1).action is Action.TURN_RIGHT
