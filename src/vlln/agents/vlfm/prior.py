"""How likely the target is near what the agent sees: a co-occurrence prior over categories.

VLFM scores each frame by how much it looks like the target is ahead (a vision-language
model's image-text similarity). Our agent sees objects only through its detector, so it
scores a frame from the categories the detector reports, with statistics learned from the
training houses (:mod:`.build`, shipped as ``data/cooccurrence.json``):

* ``in_room[c][r]``: the share of rooms of type ``r`` that hold an instance of category ``c``;
* ``together[t][c]``: the share of rooms holding ``c`` that also hold ``t``;
* ``rooms[r]``: how many rooms of each type the training houses have.

The simulator's images carry no room labels, so the room the agent looks into is inferred
from the categories in view (naive Bayes over ``in_room``, starting from the room-type
frequencies); with nothing detected the frame's value is the room prior alone: the chance
that a room of unknown type holds the target.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any

from vlln.errors import DataFormatError

PRIOR_FILE = "cooccurrence.json"
_UNSEEN = 0.01  # floor of in_room for the naive Bayes update (a category never seen there)


@dataclass(frozen=True)
class CooccurrencePrior:
    """The learned tables (module doc) and the scoring of one frame."""

    rooms: Mapping[str, int]
    in_room: Mapping[str, Mapping[str, float]]
    together: Mapping[str, Mapping[str, float]]

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> CooccurrencePrior:
        try:
            return cls(dict(data["rooms"]), dict(data["in_room"]), dict(data["together"]))
        except (KeyError, TypeError) as error:
            raise DataFormatError(
                f"{PRIOR_FILE}: not a co-occurrence prior ({error}); rebuild it with "
                "python -m vlln.agents.vlfm.build"
            ) from None

    def room_belief(self, seen: Mapping[str, float]) -> dict[str, float]:
        """P(room type | categories seen in one view), each category counted once."""
        total = sum(self.rooms.values())
        logs = {room: math.log(count / total) for room, count in self.rooms.items() if count}
        for category in seen:
            shares = self.in_room.get(category)
            if shares is None:
                continue  # a category no training house has tells nothing about the room
            for room in logs:
                logs[room] += math.log(max(shares.get(room, 0.0), _UNSEEN))
        top = max(logs.values())
        weights = {room: math.exp(value - top) for room, value in logs.items()}
        norm = sum(weights.values())
        return {room: weight / norm for room, weight in weights.items()}

    def room_value(self, target: str, seen: Mapping[str, float]) -> float:
        """Chance that the room in view holds the target, over the inferred room types."""
        shares = self.in_room.get(target, {})
        belief = self.room_belief(seen)
        return sum(p * shares.get(room, 0.0) for room, p in belief.items())

    def frame_value(self, target: str, seen: Mapping[str, float]) -> float:
        """The value of one view for finding ``target``; ``seen``: category -> pixels.

        The mean of the room term and the pixel-weighted co-occurrence of the target with
        the categories in view; the room term alone when nothing is seen."""
        room = self.room_value(target, seen)
        pixels = sum(seen.values())
        if pixels <= 0:
            return room
        with_target = self.together.get(target, {})
        objects = sum(n * with_target.get(c, 0.0) for c, n in seen.items()) / pixels
        return 0.5 * (room + objects)


@cache
def shipped_prior() -> CooccurrencePrior:
    """The prior shipped with the package (learned from the mp3d training houses)."""
    text = resources.files("vlln.agents.vlfm").joinpath("data", PRIOR_FILE).read_text()
    return CooccurrencePrior.from_json(json.loads(text))
