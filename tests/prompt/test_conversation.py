"""The conversation layout of docs/reference-formats.md §4, checked against literal reference
text."""

from __future__ import annotations

import random
import re

import numpy as np
import pytest

from vlln.errors import ConfigError
from vlln.prompt import (
    CONNECTIVES,
    DOWN_IMAGE_SIZE,
    LEVEL_IMAGE_SIZE,
    QUESTION_LIMIT_ANSWER,
    Conversation,
    DialogExchange,
    ImageRef,
    PixelOutput,
    StopOutput,
    TalkOutput,
    TiltDownOutput,
    Turn,
    TurnOutput,
    build_conversation,
    connective_for,
    history_frames,
    limit_answers,
    prompt_digest,
    with_answer,
    with_look_down,
    with_reply,
)

INSTRUCTION = "Search for the red chair in the bedroom."
# The reference training code's first human turn, written out once by hand.
SYSTEM = (
    "You are an autonomous navigation assistant. Your task is to Search for the red chair in "
    "the bedroom. There is an oracle can help you to complete the task in current "
    "environment, you can either choose to move or talk. If choosing to talk, please say "
    "something that can help you better to find the target object. If choosing to move, when "
    "you want to output a waypoint you need to TILT DOWN (↓) by 30 degrees then output the "
    "next waypoint's coordinates in the image. In case the next waypoint is out of view, "
    "utilize the turn actions: TURN LEFT (←) or TURN RIGHT (→) by 30 degrees. Please output "
    "STOP when you have successfully completed the task."
)


def level(*frames: int) -> tuple[ImageRef, ...]:
    return tuple(ImageRef("level", f) for f in frames)


def test_frame_zero_has_no_history_sentence() -> None:
    conversation = build_conversation(INSTRUCTION, 0, [], connective="in your sight is ")
    assert conversation.turns == (Turn("human", SYSTEM + " in your sight is <image>."),)
    assert conversation.images == level(0)


def test_history_is_spaced_frames_each_followed_by_a_newline() -> None:
    conversation = build_conversation(INSTRUCTION, 10, [], connective="you can spot ")
    history = "<image>\n" * 8
    expected = SYSTEM + f" These are your historical observations: {history}. you can spot <image>."
    assert conversation.turns == (Turn("human", expected),)
    assert conversation.images == level(0, 1, 2, 3, 5, 6, 7, 9, 10)


def test_dialog_block_follows_the_image_of_its_frame() -> None:
    dialogs = [DialogExchange(4, "Is it near the bed?", "Yes, to the left of the bed.")]
    conversation = build_conversation(INSTRUCTION, 10, dialogs, connective="there is ")
    history = (
        "<image>\n<image>\n<image>\n<image>\n<image>\n"
        "<|dialog_start|><|navigator|>Is it near the bed?<|oracle|>Yes, to the left of the bed."
        "<|dialog_end|><image>\n<image>\n<image>\n<image>\n"
    )
    expected = SYSTEM + f" These are your historical observations: {history}. there is <image>."
    assert conversation.turns[0].text == expected
    assert conversation.images == level(0, 1, 2, 3, 4, 5, 6, 7, 9, 10)


def test_exchanges_of_one_frame_share_a_block_and_a_last_block_meets_the_full_stop() -> None:
    dialogs = [DialogExchange(2, "Where?", "Left."), DialogExchange(2, "Which room?", "Kitchen.")]
    conversation = build_conversation(INSTRUCTION, 3, dialogs, connective="you can see ")
    block = (
        "<|dialog_start|><|navigator|>Where?<|oracle|>Left."
        "<|navigator|>Which room?<|oracle|>Kitchen.<|dialog_end|>"
    )
    history = f"<image>\n<image>\n<image>\n{block}"
    expected = SYSTEM + f" These are your historical observations: {history}. you can see <image>."
    assert conversation.turns[0].text == expected
    assert conversation.images == level(0, 1, 2, 3)


def test_questions_at_the_current_frame_are_talk_and_answer_turns() -> None:
    dialogs = [
        DialogExchange(0, "Where is it?", "Go out of the room."),
        DialogExchange(5, "Here?", "No."),
    ]
    built = build_conversation(INSTRUCTION, 5, dialogs, connective="ahead of you is ")
    earlier_only = build_conversation(INSTRUCTION, 5, dialogs[:1], connective="ahead of you is ")
    stepwise = with_answer(with_reply(earlier_only, TalkOutput("Here?")), "No.")
    assert built == stepwise
    assert built.turns[1:] == (Turn("gpt", "<talk>Here?"), Turn("human", "No."))
    assert (
        "<|navigator|>Where is it?<|oracle|>Go out of the room.<|dialog_end|>"
        in built.turns[0].text
    )


def test_look_down_turn_and_pixel_reply() -> None:
    first = build_conversation(INSTRUCTION, 6, [], connective="you can see ")
    tilted = with_reply(first, TiltDownOutput())
    shown = with_look_down(tilted, 6, connective="you are toward the ")
    final = with_reply(shown, PixelOutput(300, 410))
    assert final.turns[1:] == (
        Turn("gpt", "<move>↓"),
        Turn("human", "you are toward the <image>."),
        Turn("gpt", "<move>300 410"),
    )
    assert final.images[-1] == ImageRef("down", 6)
    assert final.images[:-1] == first.images
    assert LEVEL_IMAGE_SIZE == (384, 384) and DOWN_IMAGE_SIZE == (640, 480)
    assert [image.size for image in final.images[-2:]] == [(384, 384), (640, 480)]


def test_every_turn_in_the_text_says_30_degrees() -> None:
    for enabled in (True, False):
        text = (
            build_conversation(INSTRUCTION, 3, [], connective="there is ", dialog_enabled=enabled)
            .turns[0]
            .text
        )
        assert text.count("by 30 degrees") == 2
        assert "15" not in text


def test_without_dialog_the_oracle_sentences_are_left_out() -> None:
    text = (
        build_conversation(INSTRUCTION, 0, [], connective="there is ", dialog_enabled=False)
        .turns[0]
        .text
    )
    assert text == (
        "You are an autonomous navigation assistant. Your task is to Search for the red chair in "
        "the bedroom. When you want to output a waypoint you need to TILT DOWN (↓) by 30 degrees "
        "then output the next waypoint's coordinates in the image. In case the next waypoint is "
        "out of view, utilize the turn actions: TURN LEFT (←) or TURN RIGHT (→) by 30 degrees. "
        "Please output STOP when you have successfully completed the task. there is <image>."
    )


@pytest.mark.parametrize(
    ("frame", "dialog_frames", "expected"),
    [
        (0, [], []),
        (1, [], [0]),
        (3, [], [0, 1, 2]),
        (8, [], [0, 1, 2, 3, 4, 5, 6, 7]),
        (10, [], [0, 1, 2, 3, 5, 6, 7, 9]),
        (100, [], [0, 14, 28, 42, 56, 70, 84, 99]),
        (100, [50, 14, 120, 100], [0, 14, 28, 42, 50, 56, 70, 84, 99]),
        (5, [5, 4, 4], [0, 1, 2, 3, 4]),
    ],
)
def test_history_frames(frame: int, dialog_frames: list[int], expected: list[int]) -> None:
    assert history_frames(frame, dialog_frames) == expected


def test_numpy_frames_are_plain_ints() -> None:
    dialogs = [DialogExchange(np.int64(2), "Q?", "A.")]
    conversation = build_conversation(INSTRUCTION, np.int64(5), dialogs, connective="there is ")  # type: ignore[arg-type]
    assert dialogs[0].frame == 2 and type(dialogs[0].frame) is int
    assert all(type(image.frame) is int for image in conversation.images)
    with pytest.raises(ConfigError, match="non-negative integer"):
        DialogExchange(2.0, "Q?", "A.")  # type: ignore[arg-type]


def reference_first_turn(
    instruction: str, frame: int, dialogs: list[DialogExchange], connective: str
) -> str:
    """The reference training code's assembly (a placeholder list joined by image tags)."""
    earlier = [d for d in dialogs if d.frame < frame]
    dialog_ids = np.array([d.frame for d in earlier], dtype=np.int32)
    if frame == 0:
        return (
            SYSTEM.replace("Search for the red chair in the bedroom.", instruction)
            + f" {connective}<image>."
        )
    history_id = np.unique(
        np.concatenate([np.linspace(0, frame - 1, 8, dtype=np.int32), dialog_ids])
    ).tolist()
    placeholder = [""] * (len(history_id) + 1)
    for n in dialog_ids.tolist():
        body = "".join(
            f"<|navigator|>{d.question}<|oracle|>{d.answer}" for d in earlier if d.frame == n
        )
        placeholder[history_id.index(n) + 1] = "<|dialog_start|>" + body + "<|dialog_end|>"
    history = "<image>\n".join(placeholder)
    system = SYSTEM.replace("Search for the red chair in the bedroom.", instruction)
    return f"{system} These are your historical observations: {history}. {connective}<image>."


def random_dialogs(rng: random.Random, frame: int) -> list[DialogExchange]:
    frames = sorted(rng.randrange(frame + 1) for _ in range(rng.randrange(6)))
    return [DialogExchange(f, f"q{i} at {f}?", f"a{i}.") for i, f in enumerate(frames)]


def test_matches_the_reference_assembly_and_counts_one_image_per_tag() -> None:
    rng = random.Random(11)
    for _ in range(300):
        frame = rng.randrange(0, 400)
        dialogs = random_dialogs(rng, frame)
        connective = rng.choice(CONNECTIVES)
        conversation = build_conversation("Find the lamp.", frame, dialogs, connective=connective)
        assert conversation.turns[0].text == reference_first_turn(
            "Find the lamp.", frame, dialogs, connective
        )
        if rng.random() < 0.5:
            conversation = with_reply(conversation, TiltDownOutput())
            conversation = with_look_down(conversation, frame, connective=connective)
            conversation = with_reply(
                conversation, PixelOutput(rng.randrange(640), rng.randrange(480))
            )
        else:
            conversation = with_reply(conversation, TurnOutput("left", rng.randrange(1, 5)))
        tags = sum(turn.text.count("<image>") for turn in conversation.turns)
        assert tags == len(conversation.images)
        levels = [image.frame for image in conversation.images if image.camera == "level"]
        assert levels[-1] == frame and levels == sorted(set(levels))


def test_parts_interleave_text_and_images() -> None:
    conversation = build_conversation(
        INSTRUCTION, 2, [DialogExchange(1, "Q?", "A.")], connective="there is "
    )
    ((role, pieces),) = conversation.parts()
    assert role == "human"
    assert [p for p in pieces if isinstance(p, ImageRef)] == list(conversation.images)
    assert pieces[1:] == [
        ImageRef("level", 0),
        "\n",
        ImageRef("level", 1),
        "\n<|dialog_start|><|navigator|>Q?<|oracle|>A.<|dialog_end|>. there is ",
        ImageRef("level", 2),
        ".",
    ]


def test_connective_is_a_pure_function_of_seed_episode_and_frame() -> None:
    picks = [connective_for(5, "ep-1", frame) for frame in range(300)]
    assert picks == [connective_for(5, "ep-1", frame) for frame in range(300)]
    assert set(picks) == set(CONNECTIVES)
    assert picks != [connective_for(6, "ep-1", frame) for frame in range(300)]
    assert picks != [connective_for(5, "ep-1", frame, look_down=True) for frame in range(300)]
    # fixed across machines and runs (training data and agents must agree)
    assert [connective_for(0, "a", f) for f in range(3)] == [
        "you can see ",
        "ahead of you is ",
        "ahead of you is ",
    ]
    assert connective_for(0, "a", 0, look_down=True) == "you can spot "
    assert connective_for(1, 17, 3) == connective_for(1, "17", 3)


def test_prompt_digest_changes_with_any_byte_of_text_or_image() -> None:
    turns = build_conversation("Search for the chair.", 0, [], connective="you can see ").turns
    image = bytes(range(256))
    digest = prompt_digest(turns, [image])
    assert len(digest) == 16 and digest == prompt_digest(turns, [bytes(range(256))])
    other_image = image[:-1] + b"\x00"
    other_text = (Turn(turns[0].role, turns[0].text.replace("chair", "chairs")),)
    other_role = (Turn("gpt", turns[0].text),)
    others = [(other_text, [image]), (other_role, [image]), (turns, [other_image])]
    others += [(turns, [image, b""]), (turns, [image[:128], image[128:]])]
    assert digest not in {prompt_digest(t, i) for t, i in others}


def test_question_limit_replaces_later_answers() -> None:
    dialogs = [DialogExchange(f, f"q{f}?", f"a{f}.") for f in range(4)]
    limited = limit_answers(dialogs, 2)
    assert [d.answer for d in limited] == [
        "a0.",
        "a1.",
        QUESTION_LIMIT_ANSWER,
        QUESTION_LIMIT_ANSWER,
    ]
    assert [d.question for d in limited] == [d.question for d in dialogs]
    assert limit_answers(dialogs, 0)[0].answer == QUESTION_LIMIT_ANSWER


def reference_limit(conversation: Conversation, limit: int) -> list[str]:
    """The reference's rule: answers are counted in the first turn's dialog blocks, then in
    the human turns after a talk; those from ``limit`` on read the question-limit answer."""
    counter = iter(range(1000))
    block = re.compile(r"<\|oracle\|>.*?<\|dialog_end\|>", re.DOTALL)

    def cut(match: re.Match[str]) -> str:
        keep = next(counter) < limit
        return match.group(0) if keep else f"<|oracle|>{QUESTION_LIMIT_ANSWER}<|dialog_end|>"

    texts = [turn.text for turn in conversation.turns]
    texts[0] = block.sub(cut, texts[0])
    for index in range(1, len(texts)):
        if conversation.turns[index - 1].text.startswith("<talk>") and next(counter) >= limit:
            texts[index] = QUESTION_LIMIT_ANSWER
    return texts


def test_question_limit_matches_the_reference_rule_with_one_question_per_frame() -> None:
    dialogs = [DialogExchange(f, f"q{f}?", f"a{f}.") for f in (0, 3, 9, 12, 20, 20)]
    for limit in range(7):
        heard = limit_answers(dialogs, limit)
        limited = build_conversation(INSTRUCTION, 20, heard, connective="there is ")
        full = build_conversation(INSTRUCTION, 20, dialogs, connective="there is ")
        assert [turn.text for turn in limited.turns] == reference_limit(full, limit)


def start(frame: int = 0) -> Conversation:
    return build_conversation(INSTRUCTION, frame, [], connective="there is ")


def build(frame: int, dialogs: list[DialogExchange], dialog_enabled: bool = True) -> Conversation:
    return build_conversation(
        INSTRUCTION, frame, dialogs, connective="there is ", dialog_enabled=dialog_enabled
    )


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (
            lambda: build_conversation(INSTRUCTION, 1, [], connective="you see "),
            "unknown connective",
        ),
        (lambda: build(1, [DialogExchange(2, "q", "a")]), "after the current frame"),
        (
            lambda: build(1, [DialogExchange(0, "q", "a")], dialog_enabled=False),
            "dialog is disabled",
        ),
        (lambda: build(-1, []), "a frame is a non-negative integer"),
        (
            lambda: build_conversation("Find <image>.", 0, [], connective="there is "),
            "instruction may not",
        ),
        (lambda: DialogExchange(0, "q", "see <image>"), "answer may not contain '<image>'"),
        (lambda: DialogExchange(0, "q<|oracle|>", "a"), "reserved marker '<|'"),
        (lambda: DialogExchange(0, "", "a"), "empty question"),
        (lambda: DialogExchange(0, "q" * 301, "a"), "longer than 300"),
        (lambda: DialogExchange(-1, "q", "a"), "non-negative"),
        (lambda: with_answer(start(), "a"), "follows a <talk>"),
        (lambda: with_answer(with_reply(start(), StopOutput()), "a"), "follows a <talk>"),
        (lambda: with_answer(with_reply(start(), TalkOutput("q")), "<image>"), "may not contain"),
        (lambda: with_reply(start(), PixelOutput(1, 1)), "needs the look-down image"),
        (lambda: with_reply(with_reply(start(), StopOutput()), StopOutput()), "follows a human"),
        (lambda: with_look_down(start(), 0), "follows a <move>↓ reply"),
        (lambda: with_look_down(with_reply(start(3), TiltDownOutput()), 2), "current frame 3"),
        (lambda: Conversation((Turn("human", "<image>"),), ()), "1 <image> tags but 0 images"),
        (lambda: Conversation((Turn("gpt", "x"),), ()), "starts with a human turn"),
    ],
)
def test_misuse_is_a_clear_error(make: object, message: str) -> None:
    with pytest.raises(ConfigError, match=re.escape(message)):
        make()  # type: ignore[operator]
