"""The candidates in the asker's view, and the words that pick the target out among them.

A candidate is an instance of the target's category that the instance-id image shows over at
least :data:`vlln.oracle.answers.VISIBLE_MIN_SHARE` of its pixels (the rule oracle's "in your
view"). Candidates are told apart by where they are in the view, how far they are, their
colour and their size, in that order: the first that sets the target apart names it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vlln.oracle.answers import VISIBLE_MIN_SHARE
from vlln.oracle.knowledge import EpisodeKnowledge
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.world.model import ObjectInstance

SIDE_GAP = 0.05  # of the view's width between candidates that "left" and "right" tell apart
DISTANCE_GAP = 0.3  # m between candidates that "nearer" and "farther" tell apart
SIZE_GAP = math.log(1.25)  # a quarter bigger is "bigger"
_NUMBERS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten")
_ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth")


@dataclass(frozen=True)
class Candidate:
    """An instance of the target's category in view."""

    instance: ObjectInstance
    column: float  # mean column of its pixels, 0 at the view's left edge, 1 at its right
    distance: float  # floor-plan metres from the asker to its box

    @property
    def log_volume(self) -> float:
        sx, sy, sz = self.instance.box.size
        return math.log(max(sx * sy * sz, 1e-9))


def candidates_in_view(
    knowledge: EpisodeKnowledge, state: AgentState, frame: Frame, category: str | None = None
) -> list[Candidate]:
    """The visible instances of ``category`` (the target's when None), left to right."""
    ids = frame.instance_ids
    values, counts = np.unique(ids[ids > 0], return_counts=True)
    category = category or knowledge.target.category
    x, _, z = state.position
    found = []
    for value, count in zip(values.tolist(), counts.tolist(), strict=True):
        instance = knowledge.index.instances.get(value)
        if instance is None or instance.category != category:
            continue
        if count < VISIBLE_MIN_SHARE * ids.size:
            continue
        column = float(np.nonzero(ids == value)[1].mean()) / ids.shape[1]
        found.append(Candidate(instance, column, instance.box.plan_distance(x, z)))
    return sorted(found, key=lambda c: c.column)


def target_among(knowledge: EpisodeKnowledge, candidates: list[Candidate]) -> Candidate | None:
    return next((c for c in candidates if c.instance.id == knowledge.target.id), None)


def place(candidates: list[Candidate], target: Candidate, value: str) -> int | None:
    """The target's place among the candidates by ``value`` (``column``, ``distance`` or
    ``log_volume``), 0 for the lowest; None when another is too close to it to tell."""
    gap = {"column": SIDE_GAP, "distance": DISTANCE_GAP, "log_volume": SIZE_GAP}[value]
    mine = getattr(target, value)
    others = [getattr(c, value) for c in candidates if c is not target]
    if any(abs(other - mine) < gap for other in others):
        return None
    return sum(other < mine for other in others)


_ENDS = {"column": ("left", "right"), "distance": ("near", "far"), "log_volume": ("small", "big")}
_DEGREES = {  # (value, two candidates?) -> the comparative or superlative
    ("near", True): "nearer",
    ("near", False): "nearest",
    ("far", True): "farther",
    ("far", False): "farthest",
    ("big", True): "bigger",
    ("big", False): "biggest",
    ("small", True): "smaller",
    ("small", False): "smallest",
}


def end_word(at: int, count: int, value: str) -> str:
    """ "left" or "right", "near" or "far", "small" or "big" for the ends of the order,
    "middle" for the middle one of three, "" for a place between."""
    low, high = _ENDS[value]
    if at == 0:
        return low
    if at == count - 1:
        return high
    return "middle" if count == 3 else ""


def place_phrase(at: int, count: int, value: str) -> str:
    """The words for a place: "the one on the left", "the nearest one", "the one in the
    middle", "the second biggest one", "the third one from the left"."""
    word = end_word(at, count, value)
    if value == "column":
        if word == "middle":
            return "the one in the middle"
        return f"the one on the {word}" if word else f"the {ordinal(at)} one from the left"
    if word == "middle":
        return "the one in between" if value == "distance" else "the middle-sized one"
    if word:
        return f"the {_DEGREES[word, count == 2]} one"
    if value == "distance":
        return f"the {ordinal(at)} nearest one"
    return f"the {ordinal(count - 1 - at)} biggest one"


def which_one(candidates: list[Candidate], target: Candidate) -> str:
    """The words that pick the target out: by its place in the view, its distance, its colour
    or its size, the first that tells it apart; else its place counted from the left."""
    count = len(candidates)
    for value in ("column", "distance"):
        at = place(candidates, target, value)
        if at is not None:
            return place_phrase(at, count, value)
    color = target.instance.attributes.color
    if color and all(c.instance.attributes.color != color for c in candidates if c is not target):
        return f"the {color} one"
    at = place(candidates, target, "log_volume")
    if at is not None:
        return place_phrase(at, count, "log_volume")
    return f"the {ordinal(candidates.index(target))} one from the left"


def ordinal(at: int) -> str:
    """ "first" for 0, "second" for 1, ..."""
    return _ORDINALS[at] if at < len(_ORDINALS) else f"{at + 1}th"


def place_in_view(candidate: Candidate) -> str:
    """Where one candidate is in the view: "in front of you", "on the left of your view"."""
    if candidate.column < 1 / 3:
        return "on the left of your view"
    if candidate.column > 2 / 3:
        return "on the right of your view"
    return "in front of you"


def number_word(count: int) -> str:
    return _NUMBERS[count] if count < len(_NUMBERS) else str(count)


def plural(category: str) -> str:
    """The plural of a category name: "chairs", "boxes", "bodies", "shelves"; "blinds"
    stays."""
    if category.endswith(("lf", "knife")):
        return f"{category[:-1] if category.endswith('f') else category[:-2]}ves"
    if category.endswith(("ss", "sh", "ch", "x")):
        return f"{category}es"
    if category.endswith("s"):
        return category  # "blinds"
    if category.endswith("y") and category[-2:-1] not in "aeiou":
        return f"{category[:-1]}ies"
    return f"{category}s"


def counted(count: int, category: str) -> str:
    """ "one chair", "three chairs"."""
    return f"{number_word(count)} {category if count == 1 else plural(category)}"
