"""Which kind of help a question asks for beyond the paper's four types, if any.

A small set of readable word patterns, tried in a fixed order, over the question's words in
lower case with contractions spelled out and typing slips in cue words corrected (a word of
five letters or more becomes the cue word of six or more within one slip in five, as
:mod:`vlln.oracle.classifier.entities` corrects house words; slips of short cue words and
real words near a cue word are listed). A question that matches no
pattern is the paper's, answered by the rule oracle. The patterns leave the paper's questions
alone ("Is this the one?", "Am I close?", "What is next to it?", "Is it on the floor?").
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
    object_names,
    vocabulary_words,
)
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


@dataclass(frozen=True)
class HelpRequest:
    """A recognised question: its kind and what it names."""

    kind: HelpKind
    text: str  # the normalised words the patterns read
    yes_no: bool = False  # "is it the one on the left?" rather than "which one?"
    dimension: Dimension | None = None
    asked: tuple[str, ...] = ()  # the values named: "left", "near", "big", colours
    floor_claim: FloorClaim | None = None
    in_view: bool = False  # a count of what the asker sees ("how many can I see?")


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
    "neighborhood vicinity another"
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

# --- the patterns, tried in this order ------------------------------------------------------

_STOREY = r"(floors?|storeys?|story|stories|levels?)(?! lamp)"
_FLOOR = re.compile(
    r"\b(upstairs|downstairs|up stairs|down stairs|(go|walk|climb|head) (up|down) the stairs|"
    r"(take|use|climb) the stairs|(how many|number of) " + _STOREY + r"|floor level|"
    r"(wrong|right|correct|same|this|my|other|another|different|which|what|upper|lower|top|"
    r"ground|bottom|first|second|third|next) "
    + _STOREY
    + r"|(up|down) (a|one) "
    + _STOREY
    + r"|floor (above|below)|(one|two|three|single|multi) ?(storey|story|level|floor)s?|"
    r"(floor|level|storey) (i am|i was|i started|we are|with the|as the|of the)|"
    r"(share|shares|sharing) (a|the) (floor|level|storey)|(entrance|entry|ground|street) level|"
    r"level with the)\b"
)
# "how many chairs", "is there another one": a count of objects, not of steps or rooms.
_COUNT = re.compile(
    r"\b(how many|number of|(is|are) there (any )?(other|several|many|multiple|two|three|"
    r"another|only one|more(?! than))|more than one|only one)( (other|more|such|of))? ?"
    r"(?P<thing>\w*)"
)
# "how many drawers does the dresser have?" counts parts of one object, not objects.
_OWN_PARTS = re.compile(
    r"\b(does|do|has|have) (the|this|that|a|an|it|its) (?!house|home|building|place|flat)\w+"
)
_COUNTED = frozenset({"them", "these", "those", "it", "one", "ones", "the", "this", "that", ""})
_COUNTED_VERBS = frozenset({"are", "is", "can", "could", "do", "does", "of", "in", "there"})
# Counts of things that are not objects: "how many steps?", "how many floors?".
_NOT_OBJECTS = frozenset(
    {"steps", "step", "questions", "question", "meters", "metres", "turns", "degrees", "times"}
    | {"minutes", "seconds", "rooms", "floors", "storeys", "stories", "levels", "more"}
)
_MORE_COUNT = re.compile(
    r"\b(total number|count (the|all|them|up)|is (this|that|it) the only|(the )?only (one|\w+) "
    r"in (the|this|that) (house|room|place|home)|a second (one|\w+)|more than (one|two|three|"
    r"four|five|six|\d+)|(a lot of|lots of|several|many) \w+ (in the house|or (just )?a few)|"
    r"(is|are) there (more|other|any other|a lot|lots)|any other \w+ (in|like|besides))\b"
)
_IN_VIEW = re.compile(
    r"\b(in (my |your )?view|(can|do) (i|we) see|i (can )?see|from (here|where i am)|in sight|"
    r"visible|in front of me)\b"
)
_WINDOW = re.compile(r"\bwindows?\b")
_NEAR_WORDS = re.compile(
    r"\b(near|by|next to|beside|under|underneath|beneath|below|close|adjacent|facing|against|"
    r"in front of)\b"
)
_PASSED = re.compile(
    r"\b(have|did) (i|we) (already )?(seen|see|walk into|walked into|been in) (it|the room with)\b|"
    r"\b((did|have|had|has) (i|we) (already |just )?(pass|passed|miss|missed|overshoot|"
    r"overshot|(go|gone|went|walk|walked) (past|by))|(i|we) (think (i|we) )?(already |just )?"
    r"(passed|missed|overshot|(went|walked) (past|by))) (it|the|them)\b"
)
_CLOSER = re.compile(
    r"\b((am i|are we|i am|we are|is the agent)( \w+)? (getting|going|moving|heading|walking|"
    r"coming) (any )?(closer|nearer|farther|further|warmer|colder|hotter)|am i( \w+)? (closer|"
    r"nearer|farther|further|warmer|colder|hotter)|(did|have) i (get|got|gotten) (any )?(closer|"
    r"nearer|farther|further)|(closer|nearer) (now|than (before|earlier|when|at))|"
    r"(closer|nearer) or (farther|further)|(getting )?warmer or colder|"
    r"(is it|getting) (warmer|colder|hotter))\b"
)
_REROUTE = re.compile(
    r"\b((i|we) (am|are|think i am|got|have got|feel|seem to be)( a bit| so| totally| "
    r"completely| really| kind of| kinda)? (lost|stuck|confused|disoriented)|am i lost|"
    r"lost (track|my way|my bearings)|no idea where (i am|to go)|do not know where (i am|to go)|"
    r"(going|walking) (around )?in circles|help (me |us )?(get|getting|find|finding|reach|"
    r"navigate)|got lost)\b|\b(can|could|would) you help( me| us)?( please)?$|^(please )?help"
    r"( me)?( please)?$|^(so |totally |completely )?lost\b|\bback on track\b|"
    r"\b(walked|walking|going|gone) in (a )?(loop|circle)s?\b|\b(have|did) (i|we) (already )?"
    r"(been|visited|walked) (in |into |through )?(this|here|that)\b|\bbeen (here|in this room) "
    r"before\b|\b(haven t|have not|not yet) (visited|been|explored)\b|was that a mistake\b|"
    r"\bwhere am i relative to\b"
)
_CONFIRMATION = re.compile(
    r"^((are|do) )?(you|you are) (really |very |absolutely )?(sure|certain|positive|confident)"
    r"( about (it|that|this)| of (it|that|this)| (that|this|it)( one)? (is|is not|isnt)( it| the"
    r" one| right| correct| the right one)?)?$|^how (sure|"
    r"certain) are you$|^(really|sure|certain)$|\bis (that|this|it) (really|definitely|"
    r"certainly) (it|the one)\b|\b(are you|you are) (really |very |absolutely |completely )?(sure|"
    r"certain|positive|confident)\b|\bhow (sure|certain|confident)\b|\bdouble ?check\b|"
    r"\b(can|could) you confirm\b|\bfinal answer\b|\b(be|are you) (mistaken|wrong)\b|"
    r"\bconfusing (it|them)\b|\bjust guessing\b|\b(can|could) you tell from (here|this)\b|"
    r"\b(is|it is) (that|this|it) definitely\b|\b(is it possible|could it be) (it is |its )?(the "
    r"other|another|a different)\b"
)
_THE_ONES = (
    r"(\b(the|this|that|which) (\w+ )?ones?\b|\bof (them|these|those|the two)\b|\bones? or\b)"
)
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
_WHICH = re.compile(
    r"\bwhich (one( of (them|these|those|the two))?|of (them|these|those|the two))( \w+)? "
    r"(is (it|the target|the goal|the one|yours|mine|the right one|the correct one)|(do|did) "
    r"you mean)\b|^which (one|of them)( is it)?$"
)
# "which one?", "between the white chair and the black chair", "the one by the door or ...".
_CHOICE = re.compile(
    r"\bwhich (one|ones|of (them|these|those|the))\b|^which$|\bwhich is (the one|it|yours)\b|"
    r"\bbetween the \w+( \w+)? and the\b|\bbetween the .* and the ones?\b|"
    r"\bthe (one|\w+ one) .*\bor (the|by|in|on|with)\b|\b(\w+) (one )?or (the )?(\w+ ){1,2}one\b|"
    r"\b(front|back|first|second|top|bottom) one or\b|\bor (the )?ones?\b|"
    r"\bor (to |on )?the (left|right)\b|\bthe (\w+ )?(?P<noun>\w+) or the (\w+ )?(?P=noun)\b"
)
_NEIGHBOURHOOD = re.compile(
    r"\b(what (else )?(is|are)( there)? around (it|the (target|goal|\w+))|(which|what) (things|"
    r"objects|furniture|items) (is|are) (around|near|next to|by|beside|close to)|what else "
    r"(is|are) (near|next to|by|beside|close to) it|(its|the) (surroundings|neighbou?rhood|"
    r"immediate vicinity)|(surrounds|surrounding) (it|the)|anything (around|near|by) (it|the))\b|"
    r"\bwhat (is|are)( there)? (directly |right )?(on top of|across from|opposite|on (either|each"
    r"|both) sides? of|behind|above|below|underneath) (it|the)\b"
)
_SIMPLE = (
    (HelpKind.PASSED, _PASSED),
    (HelpKind.CLOSER, _CLOSER),
    (HelpKind.REROUTE, _REROUTE),
    (HelpKind.CONFIRMATION, _CONFIRMATION),
)


@lru_cache(maxsize=4096)
def recognised(text: str) -> HelpRequest | None:
    """The help ``text`` asks for beyond the paper's questions; None for a paper question."""
    words = normalised(asked_sentence(text))
    if not words:
        return None
    yes_no = words.split()[0] in YES_NO_OPENERS and " or " not in f" {words} "
    if _counts_objects(words):
        return HelpRequest(HelpKind.COUNT, words, yes_no, in_view=bool(_IN_VIEW.search(words)))
    if _FLOOR.search(words):
        return HelpRequest(HelpKind.FLOOR, words, yes_no, floor_claim=_floor_claim(words))
    comparison = _comparison(words, yes_no)
    if comparison is not None and " or " in words:  # "by the window or by the door?"
        return comparison
    if _WINDOW.search(words) and _NEAR_WORDS.search(words):
        return HelpRequest(HelpKind.WINDOW, words, yes_no)
    for kind, pattern in _SIMPLE:
        if pattern.search(words):
            return HelpRequest(kind, words, yes_no)
    if comparison is not None:
        return comparison
    if _NEIGHBOURHOOD.search(words):
        return HelpRequest(HelpKind.NEIGHBOURHOOD, words)
    return None


def _counts_objects(words: str) -> bool:
    """Whether the question asks how many objects there are: what it counts is "them", "one"
    or a catalogue name."""
    if _OWN_PARTS.search(words):
        return False
    if _MORE_COUNT.search(words):
        return True
    for match in _COUNT.finditer(words):
        thing = match["thing"]
        if thing in _NOT_OBJECTS:
            continue
        if match[1] in ("how many", "number of") or thing in _COUNTED:
            return True
        if thing in _COUNTED_VERBS or thing.rstrip("s") in _object_words():
            return True
    return False


@lru_cache(maxsize=1)
def _object_words() -> frozenset[str]:
    """Single words of the catalogue's names ("lamp" of "floor lamp"), rooms' words left out."""
    words = {word for name in object_names() for word in name.split()}
    return frozenset(words - {word for room in ROOM_SYNONYMS for word in room.split()})


def _comparison(words: str, yes_no: bool) -> HelpRequest | None:
    """A choice between candidates: a side, nearness, size or colour said of "one", or
    "which one?" and "the X or the Y?" about things of one kind."""
    if re.search(_THE_ONES, words) is None and _CHOICE.search(words) is None:
        return None
    tokens = words.split()
    sides = [_SIDES[w] for w in tokens if w in _SIDES]
    if re.search(r"\b(on|to|at) (the|your) right\b", words) or (sides and "right" in tokens):
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
    if _WHICH.search(words) or _CHOICE.search(words):
        return HelpRequest(HelpKind.COMPARISON, words, False, Dimension.ANY)
    return None


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
    if re.search(r"\b(upstairs|up stairs|up the stairs|climb)\b", words):
        return FloorClaim.UP
    if re.search(r"\b(downstairs|down stairs|down the stairs)\b", words):
        return FloorClaim.DOWN
    if re.search(r"\b(wrong|other|another|different)\b", words):
        return FloorClaim.OTHER
    if re.search(r"\b(right|correct|same|this|my)\b", words):
        return FloorClaim.SAME
    return None
