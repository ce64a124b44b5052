"""What the frontier agent asks the oracle and how it reads instructions and answers.

The oracle speaks plain sentences ("It is red.", "Turn left about 60 degrees.", "No, the one I
mean is red."). The parsers pull out only what the policy can act on: attribute values from a
known vocabulary, a yes or a no, and a turn angle. Text they cannot read means "no
information", never a guess, so a paraphrasing oracle degrades the agent instead of misleading
it.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np

from vlln.tasks.spec import REFUSAL_MESSAGE
from vlln.world.materials import COLORS, MATERIALS
from vlln.world.model import Attributes

# Attribute names the agent can filter candidates by (fields of Attributes).
FILTER_ATTRIBUTES: tuple[str, ...] = ("color", "material", "texture", "shape", "size")
# Attributes an answer about the target is read for; shapes are too often nouns ("desk").
ANSWER_ATTRIBUTES: tuple[str, ...] = ("color", "material", "texture", "size")

ATTRIBUTE_TEMPLATES: dict[str, tuple[str, ...]] = {
    "color": ("What color is the {category}?", "What is the color of the {category}?"),
    "material": ("What material is the {category} made of?",),
}
DISAMBIGUATION_TEMPLATES: tuple[str, ...] = (
    "Is this the {category} you are looking for?",
    "Is this the {category} you mean?",
)
ROUTE_TEMPLATES: tuple[str, ...] = (
    "Which way should I go?",
    "Which direction should I go to find the {category}?",
)
# The phrasings of each kind of question the agent asks.
TEMPLATES: dict[str, tuple[str, ...]] = {
    "attribute": ATTRIBUTE_TEMPLATES["color"],
    "route": ROUTE_TEMPLATES,
    "disambiguation": DISAMBIGUATION_TEMPLATES,
}

# Words other than the value itself that name a value ("wooden chair" = material wood).
_VALUE_WORDS: dict[tuple[str, str], tuple[str, ...]] = {
    ("material", "wood"): ("wooden",),
    ("material", "plain"): ("painted",),
    ("material", "tile"): ("tiled",),
    ("material", "foliage"): ("leafy",),
    ("size", "medium"): ("medium-sized",),
}
# Words that end the target's noun phrase in an instruction: rooms, relations, clauses.
_PHRASE_END = frozenset({"in", "on", "next", "near", "under", "above", "that", "and", "which"})
_WORD = re.compile(r"[a-z0-9]+(?:-[a-z0-9]+)*")
_ARRIVED = ("you are there", "you have arrived", "you are here", "next to you")
# Phrases whose "right" is not a direction.
_NOT_DIRECTIONS = ("right next to", "right here", "right there", "right in front")
_DEGREES = re.compile(r"(\d+(?:\.\d+)?)\s*(?:degrees?|°)")
_TURN_STEP_DEG = 30.0  # a bare "turn left" means one turn step


@dataclass(frozen=True)
class Vocabulary:
    """Phrases (as word tuples) that name each attribute value, for longest-match parsing."""

    phrases: tuple[tuple[tuple[str, ...], str, str], ...]  # (words, attribute, value)

    @staticmethod
    def from_attributes(
        known: Iterable[Attributes], names: Iterable[str] = FILTER_ATTRIBUTES
    ) -> Vocabulary:
        """All values of the named attributes seen in ``known``, plus every colour and
        material name, each with its alternative words."""
        names = tuple(names)
        values: set[tuple[str, str]] = set()
        for attributes in known:
            for name in names:
                value = getattr(attributes, name)
                if value:
                    values.add((name, value))
        if "color" in names:
            values.update(("color", c) for c in COLORS)
        if "material" in names:
            values.update(("material", m) for m in MATERIALS)
        phrases: list[tuple[tuple[str, ...], str, str]] = []
        for name, value in sorted(values):
            for text in (value, *_VALUE_WORDS.get((name, value), ())):
                words = tuple(_WORD.findall(text.lower()))
                if words:
                    phrases.append((words, name, value))
        return Vocabulary(tuple(phrases))

    def restricted(self, names: Iterable[str]) -> Vocabulary:
        keep = set(names)
        return Vocabulary(tuple(p for p in self.phrases if p[1] in keep))

    def parse(self, text: str) -> dict[str, str]:
        """Attribute values named in ``text``; longer phrases win ("dark brown" over "brown"),
        and for each attribute the first value in the text counts."""
        words = _WORD.findall(text.lower())
        matches: list[tuple[int, int, str, str]] = []  # (start, end, attribute, value)
        for phrase, name, value in self.phrases:
            n = len(phrase)
            for start in range(len(words) - n + 1):
                if tuple(words[start : start + n]) == phrase:
                    matches.append((start, start + n, name, value))
        matches.sort(key=lambda m: (-(m[1] - m[0]), m[0]))
        taken = [False] * len(words)
        chosen: list[tuple[int, str, str]] = []
        for start, end, name, value in matches:
            if not any(taken[start:end]):
                taken[start:end] = [True] * (end - start)
                chosen.append((start, name, value))
        found: dict[str, str] = {}
        for _, name, value in sorted(chosen):
            found.setdefault(name, value)
        return found


def target_phrase(instruction: str) -> str:
    """The noun phrase naming the target: "Find the small red chair in the kitchen next to the
    bed." gives "small red chair", so attributes of other objects are not mistaken for the
    target's."""
    text = instruction.strip().lower()
    if text.startswith(("in the ", "on the ")) and "," in text:
        text = text.split(",", 1)[1]
    words = _WORD.findall(text)
    if "the" in words:
        words = words[words.index("the") + 1 :]
    phrase: list[str] = []
    for word in words:
        if word in _PHRASE_END:
            break
        phrase.append(word)
    return " ".join(phrase)


def stated_attributes(instruction: str, category: str, vocabulary: Vocabulary) -> dict[str, str]:
    """Attribute values the instruction states about its target.

    The noun itself is left out (the category, or the last word when a finer name replaces
    it), so a category that is also some value ("desk") does not read as an attribute.
    """
    words = target_phrase(instruction).split()
    noun = _WORD.findall(category.lower())
    if noun and words[-len(noun) :] == noun:
        words = words[: -len(noun)]
    elif words:
        words = words[:-1]
    return vocabulary.parse(" ".join(words))


def is_refusal(answer: str) -> bool:
    """Whether the oracle declined to answer because the question budget is spent."""
    return answer.strip() == REFUSAL_MESSAGE or "question limit" in answer.lower()


def parse_yes_no(answer: str) -> bool | None:
    """True for an answer that starts with yes, False for no, None otherwise."""
    words = _WORD.findall(answer.lower())
    if not words:
        return None
    if words[0] in ("yes", "yeah", "yep", "correct", "right"):
        return True
    if words[0] in ("no", "nope", "not"):
        return False
    return None


def parse_route(answer: str) -> float | None:
    """The turn the answer asks for, in radians (left positive), from its first direction.

    "Turn left about 60 degrees." gives +60°, "turn right" one turn step to the right, "go
    forward"/"straight ahead" 0, "turn around"/"turn back" 180°. None when no direction is
    named (including "you are there").
    """
    text = answer.lower()
    for phrase in _NOT_DIRECTIONS:
        text = text.replace(phrase, " ")
    keys = {
        "around": math.pi,
        "back": math.pi,
        "behind": math.pi,
        "left": 1.0,
        "right": -1.0,
        "forward": 0.0,
        "straight": 0.0,
        "ahead": 0.0,
    }
    first: tuple[int, str] | None = None
    for key in keys:
        match = re.search(rf"\b{key}\b", text)
        if match and (first is None or match.start() < first[0]):
            first = (match.start(), key)
    if first is None:
        return None
    position, key = first
    if key in ("around", "back", "behind"):
        return math.pi
    if key in ("forward", "straight", "ahead"):
        return 0.0
    sign = keys[key]
    degrees = _DEGREES.search(text[position:])
    angle = float(degrees.group(1)) if degrees else _TURN_STEP_DEG
    return sign * math.radians(min(angle, 180.0))


def parse_storey(answer: str) -> int | None:
    """+1 when the answer sends the agent upstairs, -1 downstairs, None otherwise ("It is
    upstairs, take the stairs.", "1. Go forward about 2 meters and go downstairs ...")."""
    words = _WORD.findall(answer.lower())
    for word in words:
        if word == "upstairs":
            return 1
        if word == "downstairs":
            return -1
    return None


def says_arrived(answer: str) -> bool:
    """Whether a route answer says the target is right here ("You are there.", "It is right
    next to you.")."""
    text = answer.lower()
    return any(p in text for p in _ARRIVED)


def says_too_far(answer: str) -> bool:
    """Whether a "no" to "is this the one?" means "yes, but come closer" ("No, not from here:
    you are still about 4 meters from it.")."""
    text = answer.lower()
    return "not from here" in text or "meters from it" in text


def question(templates: tuple[str, ...], category: str, rng: np.random.Generator) -> str:
    """One of the templates, drawn with ``rng``, for the target ``category``."""
    return templates[int(rng.integers(len(templates)))].format(category=category)


def matches_known(attributes: Attributes, known: Mapping[str, str]) -> bool:
    """Whether an instance's attributes agree with every known value of the target."""
    return all(getattr(attributes, name) == value for name, value in known.items())
