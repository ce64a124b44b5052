"""``sft.jsonl``, the file the training export writes and the trainer reads: its name and the
schema of one line, in one module that both import (:mod:`vlln.datagen.sft.export` writes,
:mod:`vlln.train.data` reads).

One line is one sample::

    {"id": "<house>/episode_<i>/frame_<f>/<kind>/<copy>",
     "images": [paths under the export folder, in <image> order],
     "conversations": [{"from": "human" | "gpt", "value": text}, ...]}

The conversation is the ShareGPT layout the reference's trainer reads; its text is made by
:mod:`vlln.prompt`, the functions the model agents call.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, get_args

from vlln.files import parse_json
from vlln.prompt import Turn
from vlln.prompt.conversation import Role

SFT_FILE = "sft.jsonl"
SUMMARY_FILE = "export.json"  # written last: its presence marks a complete export
_ROLES: tuple[str, ...] = get_args(Role)


@dataclass(frozen=True)
class SftRecord:
    """One sample of the export; ``images`` are paths relative to the export folder."""

    sample_id: str
    images: tuple[str, ...]
    turns: tuple[Turn, ...]

    def line(self) -> str:
        """The sample as one line of ``sft.jsonl`` (with its newline)."""
        data = {
            "id": self.sample_id,
            "images": list(self.images),
            "conversations": sharegpt(self.turns),
        }
        return json.dumps(data, ensure_ascii=False) + "\n"

    @staticmethod
    def from_line(line: bytes | str) -> SftRecord:
        """A line read back; ValueError (:class:`~vlln.errors.DataFormatError` for one that is
        not JSON), KeyError or TypeError name what is wrong with it."""
        data: Any = parse_json(line)
        turns = tuple(Turn(turn["from"], turn["value"]) for turn in data["conversations"])
        if any(turn.role not in _ROLES for turn in turns):
            raise ValueError(f"a turn's 'from' must be {' or '.join(map(repr, _ROLES))}")
        images = data["images"]
        if not isinstance(images, list):
            raise TypeError("'images' must be a list of paths")
        return SftRecord(str(data["id"]), tuple(str(path) for path in images), turns)


def sharegpt(turns: Sequence[Turn]) -> list[dict[str, str]]:
    """Turns as the ``conversations`` of a line."""
    return [{"from": turn.role, "value": turn.text} for turn in turns]
