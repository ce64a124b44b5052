"""The one prompt and the one output grammar of every navigation model.

The training export and every model agent build the model's conversation with
``build_conversation`` (then ``with_reply`` / ``with_answer`` / ``with_look_down``) and read
its answers with ``read_output``, so training and evaluation cannot drift. The text is the
reference training code's, byte for byte (``vlln.prompt.text``); ``docs/prompt.md`` shows the
layout with examples and lists where we differ from the reference.
"""

from vlln.prompt.conversation import (
    Camera,
    Conversation,
    ImageRef,
    Role,
    Turn,
    build_conversation,
    connective_for,
    prompt_digest,
    with_answer,
    with_look_down,
    with_reply,
)
from vlln.prompt.grammar import MAX_OUTPUT_CHARS, format_output, read_output
from vlln.prompt.history import (
    DEFAULT_HISTORY_COUNT,
    DialogExchange,
    history_frames,
    limit_answers,
)
from vlln.prompt.outputs import (
    MAX_QUESTION_CHARS,
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
)
from vlln.prompt.text import (
    CONNECTIVES,
    DOWN_IMAGE_SIZE,
    IMAGE_TAG,
    LEVEL_IMAGE_SIZE,
    ORACLE_FAILURE_ANSWER,
    QUESTION_LIMIT_ANSWER,
)

__all__ = [
    "CONNECTIVES",
    "DEFAULT_HISTORY_COUNT",
    "DOWN_IMAGE_SIZE",
    "IMAGE_TAG",
    "LEVEL_IMAGE_SIZE",
    "MAX_OUTPUT_CHARS",
    "MAX_QUESTION_CHARS",
    "MAX_TURN_RUN",
    "ORACLE_FAILURE_ANSWER",
    "QUESTION_LIMIT_ANSWER",
    "Camera",
    "Conversation",
    "DialogExchange",
    "Direction",
    "ForwardOutput",
    "ImageRef",
    "ModelOutput",
    "ParseFailure",
    "PixelOutput",
    "Role",
    "StopOutput",
    "TalkOutput",
    "TiltDownOutput",
    "Turn",
    "TurnOutput",
    "ValidOutput",
    "build_conversation",
    "connective_for",
    "format_output",
    "history_frames",
    "limit_answers",
    "prompt_digest",
    "read_output",
    "with_answer",
    "with_look_down",
    "with_reply",
]
