"""The reference's exact sentences, in one place so that training and evaluation cannot drift.

Every string here is the reference training code's text, byte for byte (its turns are already
30°; only its evaluation prompt says 15°). ``SYSTEM_TEXT`` is followed by the history sentence
and the current frame; see ``docs/prompt.md`` for the whole layout.
"""

from __future__ import annotations

from typing import Final

IMAGE_TAG: Final = "<image>"

# The first human turn starts with this; ``{instruction}`` is the episode's instruction,
# which ends with its own full stop (the reference puts no full stop after it).
SYSTEM_TEXT: Final = (
    "You are an autonomous navigation assistant. Your task is to {instruction} "
    "There is an oracle can help you to complete the task in current environment, you can "
    "either choose to move or talk. If choosing to talk, please say something that can help "
    "you better to find the target object. If choosing to move, when you want to output a "
    "waypoint you need to TILT DOWN (↓) by 30 degrees then output the next waypoint's "
    "coordinates in the image. In case the next waypoint is out of view, utilize the turn "
    "actions: TURN LEFT (←) or TURN RIGHT (→) by 30 degrees. Please output STOP when you have "
    "successfully completed the task."
)

# Without dialog the reference has only an evaluation prompt; ours is the training text with
# the two sentences about the oracle left out (and 30° turns).
SYSTEM_TEXT_NO_DIALOG: Final = (
    "You are an autonomous navigation assistant. Your task is to {instruction} "
    "When you want to output a waypoint you need to TILT DOWN (↓) by 30 degrees then output "
    "the next waypoint's coordinates in the image. In case the next waypoint is out of view, "
    "utilize the turn actions: TURN LEFT (←) or TURN RIGHT (→) by 30 degrees. Please output "
    "STOP when you have successfully completed the task."
)

HISTORY_INTRO: Final = " These are your historical observations: "

# The reference's "conjunctions", each with its trailing space, in the reference's order.
CONNECTIVES: Final[tuple[str, ...]] = (
    "you can see ",
    "in front of you is ",
    "there is ",
    "you can spot ",
    "you are toward the ",
    "ahead of you is ",
    "in your sight is ",
)

DIALOG_START: Final = "<|dialog_start|>"
DIALOG_END: Final = "<|dialog_end|>"
NAVIGATOR: Final = "<|navigator|>"
ORACLE: Final = "<|oracle|>"

TALK_TAG: Final = "<talk>"
MOVE_TAG: Final = "<move>"
STOP_WORD: Final = "STOP"
LEFT_ARROW: Final = "←"
RIGHT_ARROW: Final = "→"
DOWN_ARROW: Final = "↓"
UP_ARROW: Final = "↑"

# Markers a question or an answer may not contain: they would forge a tag, an image or a
# dialog block in the prompt.
RESERVED_MARKERS: Final[tuple[str, ...]] = (IMAGE_TAG, "<|", "|>", TALK_TAG, MOVE_TAG)

# The answer the training data shows once the question limit is reached (reference training
# code), and the one the reference oracle gives when it cannot answer.
QUESTION_LIMIT_ANSWER: Final = (
    "Sorry, you have reached the question limit. No further answers are available."
)
ORACLE_FAILURE_ANSWER: Final = "Sorry, I can not answer your question now."

# (width, height) of the pictures a model is shown.
LEVEL_IMAGE_SIZE: Final = (384, 384)
DOWN_IMAGE_SIZE: Final = (640, 480)
