"""The conversation a navigation model is shown for one decision, built by one function.

``build_conversation`` writes the first human turn (system text, history with dialog blocks,
a connective, the current frame) and the talk/answer turns of questions already asked at the
current frame; ``with_reply``, ``with_answer`` and ``with_look_down`` append later turns. The
training export and every model agent call these same functions, so what an agent sends for a
recorded state is the text the export writes for it. Each ``<image>`` tag stands for the
entry of ``Conversation.images`` at the same position.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal, TypeAlias

from vlln.errors import ConfigError
from vlln.prompt.grammar import format_output
from vlln.prompt.history import (
    DEFAULT_HISTORY_COUNT,
    DialogExchange,
    check_dialog_text,
    frame_index,
    history_frames,
    history_text,
)
from vlln.prompt.outputs import PixelOutput, TalkOutput, TiltDownOutput, ValidOutput
from vlln.prompt.text import (
    CONNECTIVES,
    DOWN_IMAGE_SIZE,
    HISTORY_INTRO,
    IMAGE_TAG,
    LEVEL_IMAGE_SIZE,
    SYSTEM_TEXT,
    SYSTEM_TEXT_NO_DIALOG,
    TALK_TAG,
)

Role: TypeAlias = Literal["human", "gpt"]
Camera: TypeAlias = Literal["level", "down"]


@dataclass(frozen=True)
class ImageRef:
    """The picture an ``<image>`` tag stands for: the level or look-down view at ``frame``."""

    camera: Camera
    frame: int

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) the picture is sent at."""
        return LEVEL_IMAGE_SIZE if self.camera == "level" else DOWN_IMAGE_SIZE


@dataclass(frozen=True)
class Turn:
    role: Role
    text: str


@dataclass(frozen=True)
class Conversation:
    """Turns starting with a human one; ``images`` in the order of their tags in all turns."""

    turns: tuple[Turn, ...]
    images: tuple[ImageRef, ...]

    def __post_init__(self) -> None:
        # A value object built per prompt and training sample: it guards itself (pydantic: 3x cost).
        tags = sum(turn.text.count(IMAGE_TAG) for turn in self.turns)
        if tags != len(self.images):
            raise ConfigError(f"{tags} <image> tags but {len(self.images)} images")
        if not self.turns or self.turns[0].role != "human":
            raise ConfigError("a conversation starts with a human turn")

    def parts(self) -> list[tuple[Role, list[str | ImageRef]]]:
        """Each turn as text pieces and images in order, for chat APIs that take both."""
        images = iter(self.images)
        result: list[tuple[Role, list[str | ImageRef]]] = []
        for turn in self.turns:
            pieces: list[str | ImageRef] = []
            for index, text in enumerate(turn.text.split(IMAGE_TAG)):
                if index:
                    pieces.append(next(images))
                if text:
                    pieces.append(text)
            result.append((turn.role, pieces))
        return result


def prompt_digest(turns: Sequence[Turn], images: Sequence[bytes]) -> str:
    """A 16-hex fingerprint of exactly what a model is shown (every turn's role and text, every
    image's bytes), so an evaluation's prompts can be matched with the training samples' ones
    without storing either: any drift in text or pixels changes it."""
    digest = hashlib.blake2b(digest_size=8)
    for turn in turns:
        digest.update(f"{turn.role}\x1f{turn.text}\x1e".encode())
    for image in images:
        digest.update(len(image).to_bytes(8, "big") + image)
    return digest.hexdigest()


def connective_for(seed: int, episode_id: str | int, frame: int, *, look_down: bool = False) -> str:
    """The reference's randomly chosen connective, as a pure function of its arguments (the
    look-down turn draws its own), so the export and an agent pick the same one."""
    key = f"{seed}\x1f{episode_id}\x1f{frame}\x1f{'down' if look_down else 'level'}"
    digest = hashlib.blake2b(key.encode(), digest_size=8).digest()
    return CONNECTIVES[int.from_bytes(digest, "big") % len(CONNECTIVES)]


def build_conversation(
    instruction: str,
    frame: int,
    dialogs: Sequence[DialogExchange],
    *,
    connective: str,
    dialog_enabled: bool = True,
    history_count: int = DEFAULT_HISTORY_COUNT,
) -> Conversation:
    """The conversation for the decision at level frame ``frame``.

    ``dialogs`` are the exchanges heard so far: earlier ones go into the history, those asked
    at ``frame`` follow the first turn as ``<talk>`` and answer turns. ``instruction`` is put
    in verbatim and should end with its full stop, as the reference's instructions do.
    """
    _check_connective(connective)
    check_dialog_text("instruction", instruction)
    frame = frame_index(frame)
    if not dialog_enabled and dialogs:
        raise ConfigError("dialogs were given but dialog is disabled")
    later = [d.frame for d in dialogs if d.frame > frame]
    if later:
        raise ConfigError(f"a dialog at frame {later[0]} is after the current frame {frame}")
    frames = history_frames(frame, (d.frame for d in dialogs), history_count)
    earlier = [d for d in dialogs if d.frame < frame]
    system = SYSTEM_TEXT if dialog_enabled else SYSTEM_TEXT_NO_DIALOG
    text = system.format(instruction=instruction)
    if frames:
        text += HISTORY_INTRO + history_text(frames, earlier) + "."
    text += f" {connective}{IMAGE_TAG}."
    turns = [Turn("human", text)]
    for exchange in dialogs:
        if exchange.frame == frame:
            talk = format_output(TalkOutput(exchange.question))
            turns += [Turn("gpt", talk), Turn("human", exchange.answer)]
    images = [ImageRef("level", f) for f in frames] + [ImageRef("level", frame)]
    return Conversation(tuple(turns), tuple(images))


def with_reply(conversation: Conversation, output: ValidOutput) -> Conversation:
    """``conversation`` with the model's ``output`` as the next (assistant) turn."""
    _expect_last(conversation, "human", "a reply follows a human turn")
    if isinstance(output, PixelOutput) and conversation.images[-1].camera != "down":
        raise ConfigError("a pixel reply needs the look-down image as the last picture")
    turn = Turn("gpt", format_output(output))
    return Conversation((*conversation.turns, turn), conversation.images)


def with_answer(conversation: Conversation, answer: str) -> Conversation:
    """``conversation`` with the oracle's ``answer`` to the last ``<talk>`` as a human turn."""
    _expect_last(conversation, "gpt", "an answer follows a <talk> reply")
    if not conversation.turns[-1].text.startswith(TALK_TAG):
        raise ConfigError("an answer follows a <talk> reply")
    check_dialog_text("answer", answer)
    return Conversation((*conversation.turns, Turn("human", answer)), conversation.images)


def with_look_down(
    conversation: Conversation, frame: int, *, connective: str = CONNECTIVES[0]
) -> Conversation:
    """``conversation`` with the human turn showing the look-down image of ``frame`` (the
    current frame), after a ``<move>↓`` reply; pass ``connective_for(..., look_down=True)``
    for the reference's varied wording."""
    _check_connective(connective)
    _expect_last(conversation, "gpt", "the look-down image follows a <move>↓ reply")
    if conversation.turns[-1].text != format_output(TiltDownOutput()):
        raise ConfigError("the look-down image follows a <move>↓ reply")
    current = conversation.images[-1].frame
    if frame != current:
        raise ConfigError(f"the look-down image is of the current frame {current}, got {frame}")
    turn = Turn("human", f"{connective}{IMAGE_TAG}.")
    return Conversation(
        (*conversation.turns, turn), (*conversation.images, ImageRef("down", frame))
    )


def _check_connective(connective: str) -> None:
    if connective not in CONNECTIVES:
        raise ConfigError(
            f"unknown connective {connective!r}; use connective_for() or one of {CONNECTIVES}"
        )


def _expect_last(conversation: Conversation, role: Role, message: str) -> None:
    if conversation.turns[-1].role != role:
        raise ConfigError(message)
