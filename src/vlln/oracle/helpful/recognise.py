"""Which kind of help a question asks for beyond the paper's four types, if any.

A small set of readable word patterns, tried in a fixed order, over the question's words in
lower case with contractions spelled out and typing slips in cue words corrected (a word of
five letters or more becomes the cue word of six or more within one slip in five, as
:mod:`vlln.oracle.classifier.entities` corrects house words; slips of short cue words and
real words near a cue word are listed). The patterns are in :mod:`.patterns`. A question
that matches none is the paper's, answered by the rule oracle; they leave the paper's
questions alone ("Is this the one?", "Am I close?", "What is next to it?", "Is it on the
floor?").
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import StrEnum
from functools import lru_cache

from rapidfuzz import process
from rapidfuzz.distance import OSA

from vlln.oracle.classifier.entities import (
    FUZZY_MIN_LENGTH,
    FUZZY_SIMILARITY,
    ROOM_SYNONYMS,
    YES_NO_OPENERS,
    canonical,
    mentioned,
    object_names,
    vocabulary_words,
)
from vlln.oracle.helpful import patterns as p
from vlln.oracle.helpful.alternatives import NOT_NOUNS, named_alternatives, names_thing
from vlln.world.materials import COLORS


class HelpKind(StrEnum):
    """The kind of help a reply gave, as records store it."""

    SCHEMA = "schema"  # the paper's answer, word for word
    CLARIFICATION = "clarification"  # the paper's answer, and which of the candidates in view
    COMPARISON = "comparison"  # "the one on the left or the one on the right?"
    CONFIRMATION = "confirmation"  # "are you sure?"
    PASSED = "passed"  # "did I pass it?"
    CLOSER = "closer"  # "am I getting closer?"
    FLOOR = "floor"  # "should I go upstairs?", "which floor is it on?"
    REROUTE = "reroute"  # "I am lost"
    COUNT = "count"  # "how many chairs are there?"
    NEIGHBOURHOOD = "neighbourhood"  # "what is around it?"
    WINDOW = "window"  # "is it near a window?"
    VISITED = "visited"  # "have I been here before?", "did I skip its room?"
    DONE = "done"  # "so I am done?", "should I end the search here?"
    OFF_TOPIC = "off_topic"  # "how do I bake bread?": the paper's refusal


class Dimension(StrEnum):
    """What a comparison asks the candidates to be told apart by."""

    SIDE = "side"  # left, right, middle
    DISTANCE = "distance"  # near, far
    SIZE = "size"  # big, small
    COLOR = "color"
    ANY = "any"  # "which one is it?"


class FloorClaim(StrEnum):
    """What a floor question proposes about the target's storey, seen from the asker's."""

    UP = "up"
    DOWN = "down"
    OTHER = "other"  # "am I on the wrong floor?"
    SAME = "same"  # "is it on this floor?"


class PathTopic(StrEnum):
    """What a question about the walked path asks."""

    HERE = "here"  # "have I been here before?"
    NAMED = "named"  # "have I been in the kitchen?"
    START = "start"  # "am I in the room I started in?"
    RETRACING = "retracing"  # "am I going in circles?"
    TARGET_ROOM = "target room"  # "did I skip the room it is in?"
    ROOMS = "rooms"  # "how many rooms have I been through?"
    AREA = "area"  # "am I in the wrong part of the house?"
    ROUTE = "route"  # "was going into the laundry a mistake?", "did I detour a lot?"


class CountScope(StrEnum):
    """Where a count question counts, besides the whole house."""

    HOUSE = "house"
    VIEW = "view"  # "how many can I see?"
    ROOM = "room"  # "how many are in here?"
    WALKED = "walked"  # "how many did I pass on the way?"


@dataclass(frozen=True)
class HelpRequest:
    """A recognised question: its kind and what it names."""

    kind: HelpKind
    text: str  # the normalised words the patterns read
    yes_no: bool = False  # "is it the one on the left?" rather than "which one?"
    dimension: Dimension | None = None
    asked: tuple[str, ...] = ()  # the values named: "left", "near", "big", colours
    floor_claim: FloorClaim | None = None
    scopes: frozenset[CountScope] = frozenset()  # where a count counts
    topic: PathTopic | None = None
    rooms: tuple[str, ...] = ()  # room types named ("have I been in the kitchen?")
    reverse: bool = False  # yes means the unwanted: "was I closer before?", "first time here?"
    relation: str | None = None  # "above", "under", "behind" ... ("what is on top of it?")

    @property
    def in_view(self) -> bool:
        """A count of what the asker sees ("how many can I see?")."""
        return CountScope.VIEW in self.scopes


_CONTRACTIONS = {
    "im": "i am",
    "ive": "i have",
    "whats": "what is",
    "wheres": "where is",
    "thats": "that is",
    "theres": "there is",
    "isnt": "is not",
    "dont": "do not",
    "cant": "can not",
    "youre": "you are",
    "u": "you",
    "r": "are",
    "ur": "your",
    "pls": "please",
    "plz": "please",
    "havent": "have not",
    "hasnt": "has not",
    "hadnt": "had not",
    "didnt": "did not",
    "doesnt": "does not",
    "wasnt": "was not",
    "werent": "were not",
    "arent": "are not",
    "shouldnt": "should not",
    "wont": "will not",
    "youve": "you have",
    "weve": "we have",
    "gonna": "going to",
    "diff": "different",
}
_SLIPS = {  # slips of short cue words, too short to correct by similarity
    "sur": "sure",
    "suer": "sure",
    "shure": "sure",
    "lsot": "lost",
    "los": "lost",
    "mnay": "many",
    "mny": "many",
    "hw": "how",
    "lfet": "left",
    "letf": "left",
    "rigth": "right",
    "rihgt": "right",
    "pas": "pass",
    "teh": "the",
    "shoud": "should",
    "shuold": "should",
    "flor": "floor",
    "flore": "floor",
    "neer": "near",
    "nera": "near",
}
# Cue words of six letters or more, to which a typed word of five or more is corrected.
_CUES = (
    "upstairs downstairs staircase floors storey storeys stories window windows passed "
    "missed overshot closer nearer farther further warmer colder getting confused "
    "disoriented certain positive confident really definitely confirm middle centre "
    "center bigger smaller larger taller shorter biggest smallest largest nearest "
    "closest farthest furthest number surroundings surrounding around neighbourhood "
    "neighborhood vicinity another retracing circles visited basement searching finished"
)
_CUE_WORDS = tuple(_CUES.split())
# Real words one slip from a cue word: never corrected.
_NOT_SLIPS = (
    "close closed closes closet older holder folder ground round enter entered store stored "
    "stores large setting messed"
)
_WORD = re.compile(r"[a-z0-9]+")
_SENTENCE = re.compile(r"([^.!?;\n]*)([.!?;\n]*)")


def asked_sentence(text: str) -> str:
    """The question a message asks: its last sentence that ends with a question mark, else
    its last sentence (a message often opens with a remark, "I am a bit lost. Which way?")."""
    sentences = [
        (words, "?" in end) for words, end in _SENTENCE.findall(text) if _WORD.search(words.lower())
    ]
    questions = [words for words, asks in sentences if asks]
    return (questions or [words for words, _ in sentences] or [text])[-1]


def normalised(text: str) -> str:
    """Lower-case words, contractions spelled out, slips in cue words corrected."""
    words = _WORD.findall(text.lower().replace("'", "").replace("\u2019", ""))
    expanded = " ".join(_CONTRACTIONS.get(w, _SLIPS.get(w, w)) for w in words).split()
    return " ".join(_corrected(word) for word in expanded)


@lru_cache(maxsize=4096)
def _corrected(word: str) -> str:
    if len(word) < FUZZY_MIN_LENGTH or word in _KNOWN:
        return word
    match = process.extractOne(
        word, _CUE_WORDS, scorer=OSA.normalized_similarity, score_cutoff=FUZZY_SIMILARITY
    )
    return word if match is None else match[0]


_KNOWN = frozenset(_CUE_WORDS) | frozenset(vocabulary_words()) | frozenset(_NOT_SLIPS.split())

# Openers of a yes/no question: the paper's, and the conditional "would it be ...?".
_YES_NO = YES_NO_OPENERS | {"would", "will", "might"}
_ROOM_WORDS = sorted(ROOM_SYNONYMS)
_SIMPLE = (
    (HelpKind.PASSED, p.PASSED),
    (HelpKind.CLOSER, p.CLOSER),
    (HelpKind.REROUTE, p.REROUTE),
    (HelpKind.DONE, p.DONE),
    (HelpKind.CONFIRMATION, p.CONFIRMATION),
)


@lru_cache(maxsize=4096)
def recognised(text: str) -> HelpRequest | None:
    """The help ``text`` asks for beyond the paper's questions; None for a paper question."""
    words = normalised(asked_sentence(text))
    if not words:
        return None
    opener = words.split()[0]
    yes_no = opener in _YES_NO and " or " not in f" {words} "
    if _elsewhere(words):
        return HelpRequest(HelpKind.OFF_TOPIC, words)
    if _counts_objects(words):
        return HelpRequest(HelpKind.COUNT, words, yes_no, scopes=_scopes(words))
    if p.WITHIN_REACH.search(words) or p.BACKTRACK.search(words):
        return HelpRequest(HelpKind.PASSED, words, yes_no)  # "should I backtrack?"
    visited = _visited(words, yes_no)
    if visited is not None:
        return visited
    for kind, pattern in ((HelpKind.CONFIRMATION, p.CONFIRM_CLAIM), (HelpKind.DONE, p.DONE_MORE)):
        if pattern.search(words):  # "am I correct that the curtain by this window is it?"
            return HelpRequest(kind, words, yes_no)
    comparison = _comparison(words, yes_no, normalised(text))
    storey_room = p.STOREY_ROOM.search(words) and not p.ASKER_IN.search(words)
    if any(f.search(words) for f in (p.FLOOR, p.STAIRS, p.FLOOR_MORE)) or storey_room:
        return HelpRequest(HelpKind.FLOOR, words, yes_no, floor_claim=_floor_claim(words))
    if comparison is not None and (" or " in words or comparison.dimension != Dimension.ANY):
        return comparison  # "by the window or by the door?", "should I take the left one?"
    around = _around(words)
    if around is not None and around.relation is not None:
        return around  # "what is above the counter, cabinets or a window?"
    if p.WINDOW.search(words) and p.NEAR_WORDS.search(words):
        return HelpRequest(HelpKind.WINDOW, words, yes_no)
    for kind, pattern in _SIMPLE:
        if not pattern.search(words):
            continue
        if kind == HelpKind.CLOSER:
            either = " or " in f" {words} "  # "warmer or colder?": no yes or no
            worse = p.WORSE.search(words) is not None and not either
            return HelpRequest(kind, words, not either, reverse=worse)
        return HelpRequest(kind, words, yes_no)
    if comparison is not None:
        return comparison
    if around is not None:
        return around
    if _off_topic(words):
        return HelpRequest(HelpKind.OFF_TOPIC, words)
    return None


def _around(words: str) -> HelpRequest | None:
    """A question about what is around the target, and the relation it asks about."""
    named = (_object_words() - NOT_NOUNS) | {"floor"}  # "on a rug or the floor?"
    for pattern, relation in ((p.SUPPORT_CHOICE, "support"), (p.NEAR_CHOICE, None)):
        match = pattern.search(words)  # "on a chair, a bed or a sofa?", "near the X or the Y?"
        if match and names_thing(match["one"], named) and names_thing(match["other"], named):
            return HelpRequest(HelpKind.NEIGHBOURHOOD, words, relation=relation)
    if not (p.NEIGHBOURHOOD.search(words) or p.AROUND_MORE.search(words)):
        return None
    relation = next((name for name, pattern in p.RELATIONS if pattern.search(words)), None)
    return HelpRequest(HelpKind.NEIGHBOURHOOD, words, relation=relation)


def _visited(words: str, yes_no: bool) -> HelpRequest | None:
    """A question about the walked path: the rooms and places it went through."""
    if p.REROUTE.search(words):  # "I am lost, going in circles": the way out first
        return None
    rooms = canonical(mentioned(words, _ROOM_WORDS), ROOM_SYNONYMS)
    for topic, patterns in (
        (PathTopic.AREA, (p.AREA, p.WRONG_AREA)),
        (PathTopic.START, (p.START,)),
        (PathTopic.RETRACING, (p.RETRACING, p.ENDING_UP)),
        (PathTopic.TARGET_ROOM, (p.TARGET_ROOM, p.MISSED_ROOM)),
        (PathTopic.ROOMS, (p.ROOMS,)),
        (PathTopic.ROUTE, (p.ROUTE,)),
        (PathTopic.HERE, (p.HERE,)),
    ):
        if not any(pattern.search(words) for pattern in patterns):
            continue
        if topic == PathTopic.HERE and rooms and not re.search(r"\b(here|this)\b", words):
            topic = PathTopic.NAMED  # "have I been in the kitchen?"
        reverse = False  # "am I in the wrong part?", "is this the first time here?"
        if topic == PathTopic.AREA:
            reverse = "wrong" in words.split()
        elif topic == PathTopic.ROUTE:
            reverse = p.ROUTE_WORSE.search(words) is not None
        elif topic == PathTopic.HERE:
            reverse = p.FIRST_TIME.search(words) is not None
        return HelpRequest(
            HelpKind.VISITED, words, yes_no, topic=topic, rooms=rooms, reverse=reverse
        )
    return None


def _counts_objects(words: str) -> bool:
    """Whether the question asks how many objects there are: what it counts is "them", "one"
    or a catalogue name."""
    if p.OWN_PARTS.search(words) or p.STOREY_COUNT.search(words):
        return False
    if p.MORE_COUNT.search(words) or p.COUNT_MORE.search(words):
        return True
    for match in p.ONLY_ONE.finditer(words):
        if match["thing"] in ("one", "ones") or match["thing"].rstrip("s") in _object_words():
            return True
    for match in p.COUNT.finditer(words):
        thing = match["thing"]
        if thing in _NOT_OBJECTS:
            continue
        if match[1] in ("how many", "number of") or thing in _COUNTED:
            return True
        if thing in _COUNTED_VERBS or thing.rstrip("s") in _object_words():
            return True
    return False


_COUNTED = frozenset({"them", "these", "those", "it", "one", "ones", "the", "this", "that", ""})
_COUNTED_VERBS = frozenset({"are", "is", "can", "could", "do", "does", "of", "in", "there"})
# Counts of things that are not objects: "how many steps?", "how many floors?".
_NOT_OBJECTS = frozenset(
    {"steps", "step", "questions", "question", "meters", "metres", "turns", "degrees", "times"}
    | {"minutes", "seconds", "rooms", "floors", "storeys", "stories", "levels", "more"}
)


def _scopes(words: str) -> frozenset[CountScope]:
    """Where a count question counts: what the asker walked past, sees, or the room it is in;
    the house always."""
    scopes = {CountScope.HOUSE}
    if p.WALKED_COUNT.search(words):
        scopes.add(CountScope.WALKED)
    elif p.IN_VIEW.search(words) or p.FIELD_OF_VIEW.search(
        words
    ):  # "did I see" is the walk, not the view
        scopes.add(CountScope.VIEW)
    if p.IN_ROOM.search(words):
        scopes.add(CountScope.ROOM)
    return frozenset(scopes)


@lru_cache(maxsize=1)
def _object_words() -> frozenset[str]:
    """Single words of the catalogue's names ("lamp" of "floor lamp"), rooms' words left out."""
    words = {word for name in object_names() for word in name.split()}
    return frozenset(words - {word for room in ROOM_SYNONYMS for word in room.split()})


def _comparison(words: str, yes_no: bool, message: str) -> HelpRequest | None:
    """A choice between candidates: a side, nearness, size or colour said of "one", or
    "which one?", "the X or the Y?" and "left or right?" about things of one kind (the
    whole ``message`` says whether several are in view)."""
    side_choice = p.SIDE_CHOICE.search(words) is not None and p.SEVERAL.search(message)
    named = named_alternatives(words, _object_words())
    chosen = re.search(p.THE_ONES, words) or p.CHOICE.search(words) or side_choice or named
    if not chosen:
        return None
    if p.MOVES.search(words) and re.search(p.THE_ONES, words) is None:
        return None  # "should I turn left or right?" is the paper's step question
    tokens = words.split()
    sides = [_SIDES[w] for w in tokens if w in _SIDES]
    if p.RIGHT_SIDE.search(words) or (sides and "right" in tokens):
        sides.append("right")
    for dimension, values in (
        (Dimension.SIDE, sides),
        (Dimension.DISTANCE, [*_values(tokens, _NEARNESS), *_said_of_one(words, _PLAIN_NEARNESS)]),
        (Dimension.SIZE, [*_values(tokens, _SIZES), *_said_of_one(words, _PLAIN_SIZES)]),
        (Dimension.COLOR, _said_of_one(words, {c: c for c in COLORS})),
    ):
        if values:
            asked = tuple(dict.fromkeys(values))
            return HelpRequest(HelpKind.COMPARISON, words, yes_no, dimension, asked)
    which = p.WHICH_DIMENSION.search(words)
    if which is not None:  # "which size is the one you mean?"
        dimension = _WHICH_DIMENSIONS[which["what"]]
        return HelpRequest(HelpKind.COMPARISON, words, False, dimension)
    if p.WHICH.search(words) or p.CHOICE.search(words) or named:
        return HelpRequest(HelpKind.COMPARISON, words, False, Dimension.ANY)
    return None


# Words that tell candidates apart: canonical value by word. A plain word ("big", "near",
# "right", a colour) counts only said of a candidate ("the big one", "on the right"), since
# "is it big?" is the paper's attribute question and "the right one" means the correct one.
_SIDES = {"left": "left", "middle": "middle", "centre": "middle", "center": "middle"}
_NEARNESS = {"nearer": "near", "closer": "near", "nearest": "near", "closest": "near"}
_NEARNESS |= {"farther": "far", "further": "far", "farthest": "far", "furthest": "far"}
_SIZES = {"bigger": "big", "larger": "big", "taller": "big", "biggest": "big"}
_SIZES |= {"largest": "big", "tallest": "big", "smaller": "small", "shorter": "small"}
_SIZES |= {"smallest": "small", "shortest": "small"}
_PLAIN_NEARNESS = {"near": "near", "close": "near", "far": "far"}
_PLAIN_SIZES = {"big": "big", "large": "big", "tall": "big", "huge": "big", "small": "small"}
_PLAIN_SIZES |= {"little": "small", "short": "small", "tiny": "small"}
_WHICH_DIMENSIONS = {
    "size": Dimension.SIZE,
    "color": Dimension.COLOR,
    "colour": Dimension.COLOR,
    "side": Dimension.SIDE,
}


def _values(tokens: list[str], table: dict[str, str]) -> list[str]:
    return [table[w] for w in tokens if w in table]


def _said_of_one(words: str, table: dict[str, str]) -> list[str]:
    """Values of ``table`` said of a candidate: "the red one", "red one or ...", "or red one"."""
    found = []
    for word in sorted(table, key=len, reverse=True):  # "light gray" before "gray"
        said = rf"\b(the|or) {word} ones?\b|\b{word} ones? or\b"
        if re.search(said, words):
            found.append(table[word])
            words = re.sub(rf"\b{word}\b", " ", words)
    return found


def _floor_claim(words: str) -> FloorClaim | None:
    up = re.search(r"\b(upstairs|up stairs|up the stairs|climb|up|attic|above)\b", words)
    down = re.search(
        r"\b(downstairs|down stairs|down the stairs|down|basement|cellar|below)\b", words
    )
    if re.search(r"\b(waste|pointless|useless|no point|not worth)\b", words):
        return None  # "would going upstairs be a waste of time?": yes would mean no
    if re.search(r"\bwithout\b", words):
        return FloorClaim.SAME  # "can I reach it without taking the stairs?"
    if (up and down) or re.search(r"\b(more than one|several|multiple) (floor|level)", words):
        return None  # "up or down?", "does the house have more than one floor?"
    if up:
        return FloorClaim.UP
    if down:
        return FloorClaim.DOWN
    if re.search(r"\b(wrong|other|another|different|change|switch|stairs|staircase)\b", words):
        return FloorClaim.OTHER
    if re.search(r"\b(right|correct|same|this|my) (floor|level|storey|story)\b", words):
        return FloorClaim.SAME
    return None


def _elsewhere(words: str) -> bool:
    """Whether the question is about something outside the house ("what is the square root of
    144?", "is it going to snow?"): a topic of :data:`.patterns.ELSEWHERE`, and no word of the
    house, its objects or a move in it."""
    if p.ELSEWHERE.search(words) is None:
        return False
    tied = (_object_words() - NOT_NOUNS) | p.HOUSE_WORDS
    return not any(token in tied or token.rstrip("s") in tied for token in words.split())


def _off_topic(words: str) -> bool:
    """Whether the question asks how to do something that is no move, look or question of the
    search ("how do I bake bread?"), with no word of the search or cue word in it."""
    if p.HOW_TO.search(words) is None or re.search(r"\b(to|into|toward|towards) the\b", words):
        return False  # "how do I gte to the kichen?" is a way asked, slips and all
    return not any(token in p.ON_TOPIC_WORDS or token in _CUE_WORDS for token in words.split())
