"""The values a question names: colours, materials, rooms, "this room", a proposed step.

These are look-ups of the house vocabularies (the palette, the materials, the room types and
the catalogue's names), not language rules. A word that is in no vocabulary is matched to
the nearest vocabulary word when they are close (rapidfuzz's normalised edit similarity, at
least :data:`FUZZY_SIMILARITY`), so "bathrom" still names the bathroom; a real word so close
to a vocabulary word is usually a form of it ("tables", "woody").
"""

from __future__ import annotations

from functools import cache

from rapidfuzz import process
from rapidfuzz.distance import OSA

from vlln.oracle.topics import StepChoice
from vlln.world.catalogue.aliases import aliases_of
from vlln.world.catalogue.registry import ROOM_TYPES, default_catalogue
from vlln.world.materials import COLORS

# Canonical names of the rooms and materials a question may mention.
ROOM_SYNONYMS: dict[str, str] = {
    **{room: room for room in ROOM_TYPES},
    "living": "living room",
    "lounge": "living room",
    "hallway": "corridor",
    "hall": "corridor",
    "office": "study",
    "study room": "study",
    "restroom": "toilet",
    "washroom": "bathroom",
    "bath": "bathroom",
    "dining": "dining room",
    "storage": "storage room",
    "pantry": "storage room",
    "sports room": "gym",
    "resting room": "bedroom",
}
MATERIAL_SYNONYMS: dict[str, str] = {
    **{m: m for m in ("wood", "metal", "fabric", "leather", "glass", "plastic", "ceramic")},
    **{m: m for m in ("marble", "tile", "carpet")},
    "wooden": "wood",
    "metallic": "metal",
    "steel": "metal",
    "iron": "metal",
    "cloth": "fabric",
    "porcelain": "ceramic",
    "stone": "marble",
    "tiled": "tile",
}
THIS_ROOM = ("this room", "same room", "current room", "room i am in", "room we are in")
# First words of a yes/no question ("isn't" reads as "isn" "t").
YES_NO_OPENERS = frozenset(
    {"is", "are", "was", "were", "does", "do", "did", "can", "could", "should", "shall", "am"}
    | {"has", "have", "isn", "aren", "doesn", "don", "didn", "couldn", "shouldn", "hasn"}
)
# Normalised similarity (1 - edits / length; a swap of neighbours is one edit) a typed word
# needs to a vocabulary word: one slip in five letters.
FUZZY_SIMILARITY = 0.8
FUZZY_MIN_LENGTH = 5  # shorter words are too easily one slip from another word
_SIDES = ("left", "right")
_NOT_A_SIDE = frozenset(["here", "now", "there", "way", "direction", "track", "one", "place"])
_MOVES = frozenset(["turn", "go", "head", "move", "keep", "bear", "veer"])
_FORWARD = ("forward", "straight", "ahead", "continue", "keep going")


@cache
def object_names() -> frozenset[str]:
    """The catalogue's names and their aliases ("sofa" for a couch)."""
    names = {c.name for c in default_catalogue()}
    return frozenset(names | set(aliases_of(names)))


@cache
def category_phrases() -> tuple[str, ...]:
    """Catalogue names (and aliases) of several words, longest first, which claim their words
    first: the "kitchen" of a kitchen island is no room."""
    return tuple(sorted((n for n in object_names() if " " in n), key=lambda n: (-len(n), n)))


@cache
def vocabulary_words() -> tuple[str, ...]:
    """Single words of every vocabulary a typed word may be corrected to."""
    phrases = [*COLORS, *MATERIAL_SYNONYMS, *ROOM_SYNONYMS, *object_names()]
    return tuple(sorted({w for p in phrases for w in p.split()}))


@cache
def _vocabulary_set() -> frozenset[str]:
    return frozenset(vocabulary_words())


def corrected_words(words: list[str]) -> list[str]:
    """``words`` with each unknown word of :data:`FUZZY_MIN_LENGTH` letters or more replaced by
    the closest vocabulary word, when one is similar enough."""
    vocabulary = vocabulary_words()
    known = _vocabulary_set()
    out = []
    for word in words:
        if len(word) >= FUZZY_MIN_LENGTH and word not in known:
            match = process.extractOne(
                word, vocabulary, scorer=OSA.normalized_similarity, score_cutoff=FUZZY_SIMILARITY
            )
            word = match[0] if match is not None else word
        out.append(word)
    return out


def mentioned(text: str, words: list[str]) -> tuple[str, ...]:
    """The words (possibly several tokens long) that occur in ``text``, longest first, each
    occurrence claimed once ("light gray" is not also "gray"); catalogue names of several
    words are claimed before any."""
    found: list[str] = []
    remaining = f" {text} "
    for phrase in category_phrases():
        remaining = remaining.replace(f" {phrase} ", " | ")
    for word in sorted(words, key=len, reverse=True):
        needle = f" {word} "
        if needle in remaining:
            found.append(word)
            remaining = remaining.replace(needle, " | ")
    return tuple(found)


def canonical(words: tuple[str, ...], synonyms: dict[str, str]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(synonyms[w] for w in words))


def step_choice(words: list[str]) -> StepChoice | None:
    """The action a step question proposes, if it proposes exactly one."""
    if "or" in words or "either" in words:
        return None  # a choice between actions, not a proposal of one
    if "stop" in words:
        return StepChoice.STOP
    before = ["", *words[:-1]]
    after = [*words[1:], ""]
    sides = {
        word
        for last, word, nxt in zip(before, words, after, strict=True)
        if word in _SIDES and (last in _MOVES or word == "left" or nxt not in _NOT_A_SIDE)
    }
    if len(sides) == 1:
        return StepChoice.LEFT if "left" in sides else StepChoice.RIGHT
    text = f" {' '.join(words)} "
    if not sides and any(f" {w} " in text for w in _FORWARD):
        return StepChoice.FORWARD
    return None
