"""Offline question classification: what kind of question a navigator asked, and about what.

The paper's oracle asks a language model to sort each question into Attribute, Route,
Disambiguation or Other. Navigator questions come from a small space of intents, so weighted
phrase patterns do the same job deterministically, in microseconds and without a network.

Text is first normalised (:mod:`vlln.oracle.normalisation`: case, contractions, chat
spellings, typos), so the patterns see clean lower-case words. Every pattern that matches
adds its weight to its topic and to the topic's question type; the highest total wins, ties
going to the more specific type. A question that matches nothing is Other.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from enum import StrEnum
from typing import TypeVar

from vlln.oracle.normalisation import normalise
from vlln.oracle.protocol import QuestionType
from vlln.world.catalogue.registry import ROOM_TYPES
from vlln.world.materials import COLORS


class RouteKind(StrEnum):
    """Granularity of a route question (paper §3.2): heading, path through rooms, next action."""

    ORIENTATION = "orientation"
    PATH = "path"
    STEP = "step"


class AttributeTopic(StrEnum):
    """Which fact about the target an attribute question asks for."""

    COLOR = "color"
    MATERIAL = "material"
    TEXTURE = "texture"
    SHAPE = "shape"
    SIZE = "size"
    ROOM = "room"
    LOCATION = "location"  # "where is it?": room, placement and a neighbour
    NEARBY = "nearby"
    SUPPORT = "support"  # "what is it on?"
    CATEGORY = "category"  # "what kind of chair is it?"
    DESCRIPTION = "description"


class OtherTopic(StrEnum):
    """Questions outside the three core types that privileged knowledge can still answer."""

    AGENT_ROOM = "agent room"
    DISTANCE = "distance"
    PROGRESS = "progress"
    VISIBILITY = "visibility"
    UNKNOWN = "unknown"


class StepChoice(StrEnum):
    """The action a step question proposes ("should I turn left?")."""

    LEFT = "left"
    RIGHT = "right"
    FORWARD = "forward"
    STOP = "stop"


@dataclass(frozen=True)
class QuestionAnalysis:
    """Everything the answerers need to know about a question's wording."""

    text: str  # the normalised text
    question_type: QuestionType
    route_kind: RouteKind | None = None
    attribute: AttributeTopic | None = None
    other: OtherTopic | None = None
    yes_no: bool = False  # "is it red?" rather than "what colour is it?"
    colors: tuple[str, ...] = ()  # colour words mentioned, longest first
    materials: tuple[str, ...] = ()  # material names mentioned
    rooms: tuple[str, ...] = ()  # room types mentioned
    this_room: bool = False  # "this room", "the room I am in"
    step_choice: StepChoice | None = None


# --- patterns ------------------------------------------------------------------------------

_ROOM_SYNONYMS: dict[str, str] = {
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
_MATERIAL_SYNONYMS: dict[str, str] = {
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


def _alternatives(words: list[str]) -> str:
    return "|".join(re.escape(w) for w in sorted(words, key=len, reverse=True))


_ROOMS = _alternatives([*_ROOM_SYNONYMS, "room"])
_COLORS = _alternatives(list(COLORS))
_MATERIALS = _alternatives(list(_MATERIAL_SYNONYMS))
_YES_NO_START = re.compile(r"^(is|are|was|were|does|do|did|can|could|should|shall|am|has|have)\b")
_SUPPORTS = r"(floor|ground|wall|table|shelf|counter|desk|cabinet|something)"

_D = QuestionType.DISAMBIGUATION
_O, _P, _S = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP
_A, _X = AttributeTopic, OtherTopic
_Topic = QuestionType | RouteKind | AttributeTopic | OtherTopic

# (weight, topic, pattern): a match adds the weight to the topic and to the topic's type.
_RULES: tuple[tuple[float, _Topic, str], ...] = (
    # Disambiguation: is what I am looking at the target?
    (3, _D, r"^(is|are|was|would) (this|that|these|those)\b"),
    (2, _D, r"\b(this|that) (one|thing|object|item)\b"),
    (2, _D, r"\b(the|your) one\b"),
    (2, _D, r"\b(right|correct|same|intended|target|goal|wanted) (one|object|thing|item)\b"),
    (
        2,
        _D,
        r"\b(in front of me|i am looking at|i am facing|i see|i can see|i found|i have found"
        r"|have i found|did i find|i spotted|found it|right here|over here|before me|i got it"
        r"|i am at|i reached|have i reached|did i reach)\b",
    ),
    (4, _D, r"^is it (this|that|these|the one)\b"),
    (5, _D, r"^is .* the ((right|correct|same|target) )?(target|goal|one|object)$"),
    (4, _D, r"\bis (this|that|it) (the )?(target|goal|one|right one|correct one)\b"),
    (4, _D, r"^is it the \w+ (next to|in front of|near|beside|by) me\b"),
    (4, _D, r"^(could|can|might|would) (this|that|it) be (the|it)\b"),
    (3, _D, r"\b(is|are) (this|that) it\b|\b(this|that) (is|was) (it|the one)\b"),
    (3, _D, r"\bis (this|that|it) what you\b"),
    (
        2,
        _D,
        r"\byou (want|mean|meant|described|are describing|are talking about|are thinking of"
        r"|have in mind)\b",
    ),
    (3, _D, r"^(this|that|these|those) (?!(way|room|direction|side)\b)\w+( right| correct| yes)?$"),
    (3, _D, r"\bam i (looking at|in front of|facing|at|next to) (it|the (right|correct|target))"),
    # Route, orientation: the direction of the target.
    (4, _O, r"\b(which|what) direction\b"),
    (2, _O, r"\bdirection\b"),
    (3, _O, r"\bwhich (way|side)\b|\bpoint (me|at|to)\b|\b(should i|do i|must i) face\b"),
    (3, _O, r"\b(on|to) (my|the|your) (left|right)\b"),
    (2, _O, r"\b(heading|bearing|angle|orientation|degrees)\b|\bam i facing\b"),
    (5, _O, r"\b(relative|compared) to (me|where i am|my)\b"),
    (4, _O, r"\b(in front|ahead) (of me )?or behind\b|\bbehind (me )?or (in front|ahead)\b"),
    (3, _O, r"\bin the direction (i am|of)\b"),
    (5, _O, r"\bwhere is (it|the \w+) (from here|from me|relative|compared|in relation)"),
    (
        2,
        _O,
        r"^(is|are) (it|they|the \w+) ((somewhere|maybe|probably|still) )?"
        r"(ahead|behind|in front|straight|left|right"
        r"|(to|on) (the|my|your) (left|right))\b",
    ),
    # Route, path: a way through the house.
    (
        4,
        _P,
        r"\bhow (do|can|should|would|could|shall|must|to|will) (i |we )?(get|reach|go|find"
        r"|navigate|walk|arrive|head|make it|travel)\b",
    ),
    (4, _P, r"\b(route|path|directions)\b"),
    (3, _P, r"\bwhere (to|next|now)\b"),
    (
        4,
        _P,
        r"\bwhere (should|do|must|can|shall|could|would|will) (i|we) (need to |have to |want to )?"
        r"(go|head|walk|move|proceed"
        r"|search|look|explore|turn)\b",
    ),
    (3, _P, r"\b(guide|lead|take|show|direct|bring|help|navigate|walk|steer) (me|us)\b"),
    (2, _P, r"\b(get|go) there\b|\bway (to|there)\b"),
    (4, _P, r"\b(the|a|best|quickest|shortest|fastest) way (out|to|toward|into|through)\b"),
    (4, _P, r"\bstep by step\b"),
    (
        5,
        _P,
        r"\bwhich (room|door|doorway|hallway|corridor|exit) (should|do|must|can) (i|we)\b(?! find)",
    ),
    # Route, step: the next action.
    (
        3,
        _S,
        r"\b(should|do|must|shall|can) (i|we) (need to |have to )?(turn|go|keep|continue|stop|move"
        r"|leave|enter|exit|take|cross|follow"
        r"|walk|head|proceed|step)\b",
    ),
    (
        3,
        _S,
        r"\b(left or right|right or left|forward or|or forward|straight or|or straight|or back"
        r"|or turn|or stop)\b",
    ),
    (5, _S, r"\bwhat (should|do|shall|must|can) (i|we) do\b"),
    (5, _S, r"\b(what now|now what|what next|what is next)\b(?! to)"),
    (4, _S, r"\bnext (step|move|action|turn)\b"),
    (2, _S, r"\b(turn|go|move|head|walk) (left|right|forward|straight|back|backward|ahead)\b"),
    (2, _S, r"\b(keep going|stop here|go on|continue)\b"),
    (2, _S, r"^(should|do|shall|must|can) (i|we) .*\b(left|right)\b"),
    (3, _S, r"\b(upstairs|downstairs)\b|^(left|right|straight|forward|back|stop)$"),
    # Attribute: facts about the target.
    (4, _A.COLOR, r"\b(color|colors|colored|hue)\b"),
    (1, _A.COLOR, rf"\b({_COLORS})\b"),
    (4, _A.MATERIAL, r"\bmaterials?\b|\b(made|built|constructed) (of|from|out|with)\b"),
    (4, _A.MATERIAL, r"\bwhat (is|are) (it|they|the \w+) made\b"),
    (1, _A.MATERIAL, rf"\b({_MATERIALS})\b"),
    (
        4,
        _A.TEXTURE,
        r"\b(texture|textured|feel|feels|surface|smooth|rough|soft|glossy|pattern|patterned"
        r"|finish|striped|stripes|spotted|checkered|floral|shiny|matte)\b",
    ),
    (3, _A.DESCRIPTION, r"^(does|do) (it|they|the \w+) have\b"),
    (2, _A.CATEGORY, r"\b(is|are) (it|they|the \w+) (a|an) "),
    (4, _A.SHAPE, r"\b(shape|shaped|form|round|square|rectangular|oval|circular)\b"),
    (5, _A.SIZE, r"\bhow (big|large|small|tall|high|wide|long|heavy)\b"),
    (
        3,
        _A.SIZE,
        r"\b(size|sized|dimensions|height|width|bigger|larger|smaller|big|large|small|tall)\b",
    ),
    (4, _A.ROOM, r"\b(which|what) (room|part of the house|area|region)\b|\bsame room\b"),
    (3, _A.ROOM, rf"\bin (the|a|an|this|my|our|that|same) (\w+ )?({_ROOMS})\b"),
    (7, _A.ROOM, r"^(is|are) (it|they|the \w+) in (the|this|my|our|the same|same) room\b"),
    (
        3,
        _A.LOCATION,
        r"^(so |and )?where (\w+ )?(is|are|was) (it|the|they|this|that|your|target)\b",
    ),
    (1, _A.LOCATION, r"^where\b"),
    (3, _A.LOCATION, r"\bwhere (it|they|the \w+) (is|are|hangs|sits|stands|lies|hang|sit|stand)\b"),
    (5, _A.LOCATION, r"\bwhere (can|could|do|would|might|will|should) (i|we) find\b"),
    (3, _A.LOCATION, r"\b(can|could|do|would|might|will|should) (i|we) find (it|the|them)\b"),
    (3, _A.LOCATION, r"\b(located|location|placed|kept|stored|situated|position)\b"),
    (
        3,
        _A.NEARBY,
        r"\b(near|nearby|next to|beside|besides|close to|surrounded|neighbor|neighbors"
        r"|adjacent|surrounding|surroundings|around (it|the|them)|with it|by the)\b",
    ),
    (
        6,
        _A.SUPPORT,
        r"\bwhat is (it|the \w+) (on|sitting on|standing on|resting on|placed on|lying on"
        r"|on top of|hanging on|mounted on)\b",
    ),
    (
        4,
        _A.SUPPORT,
        rf"\b(on|sitting on|standing on|resting on|placed on|hanging on|mounted on"
        rf"|lying on) (the|a|top of) {_SUPPORTS}\b",
    ),
    (2, _A.SUPPORT, r"\b(on top of|under|underneath|below|above|hanging|mounted|against)\b"),
    (
        3,
        _A.SUPPORT,
        r"^(is|are) (it|they|the \w+) (on|sitting on|standing on|resting on|lying on|placed on"
        r"|hanging on|mounted on|on top of) (the|a|an|some|top of) (?!(left|right|way|other)\b)",
    ),
    (
        5,
        _A.CATEGORY,
        r"\b(what|which) (kind|type|sort|style|model|brand)\b|\b(category|categories)\b",
    ),
    (
        3,
        _A.CATEGORY,
        r"^what (is|are) (it|they|the (target|goal)( object)?|the object)$|\bwhat exactly\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\b(describe|description|appearance|details|detail|features|characteristics"
        r"|distinctive|distinguishing|special|unique|identify|recognize|distinguish)\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\blooks? like\b|\btell me (more |something |anything |everything )?about\b"
        r"|\b(what|everything|anything|all) you know\b|\bstands? out\b",
    ),
    (4, _A.DESCRIPTION, r"\bhow ((does|do|did) )?(it|they|the \w+) looks?\b"),
    (5, _A.DESCRIPTION, r"\bwhat (object|thing|item) (am i|are we|should i|do i|must i)\b"),
    (
        4,
        _A.DESCRIPTION,
        r"\b(more|any|some|other|a|another) (info|information|hints?|clues?|details)\b",
    ),
    (5, _A.DESCRIPTION, r"\bwhat (am i|are we|are you) (looking|searching) for\b"),
    (
        5,
        _A.DESCRIPTION,
        r"\bwhat (should|do|must|shall) (i|we) (be )?(look|looking|search|searching) for\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\bwhich (one|\w+)(?<!side)(?<!way)(?<!direction) (is it|is the (target|goal|one)"
        r"|do you mean|are you looking for|should i find|am i looking)\b",
    ),
    # Other: what privileged knowledge of the agent's state answers.
    (7, _X.AGENT_ROOM, r"\b(which|what) (room|part of the house|area|place) (am i|are we|is this)"),
    (
        7,
        _X.AGENT_ROOM,
        rf"\bwhere am i\b|\bwhere are we\b(?! (going|headed|heading))"
        rf"|^(is this|is that|are we in|is here|is this room|is this place) (the |a )?({_ROOMS})$",
    ),
    (6, _X.AGENT_ROOM, r"\b(am i|are we) in (the|a|an)\b|\b(room|place) (i am|we are) in\b"),
    (
        7,
        _X.DISTANCE,
        r"\bhow (far|close|near|long|many (steps|meters|feet|moves)|much (further|farther"
        r"|longer|more))\b",
    ),
    (4, _X.DISTANCE, r"\b(distance|far away|how far)\b"),
    (
        7,
        _X.DISTANCE,
        r"\bis (it|the \w+) (still |very )?(far|close|near|nearby)( from here| away)?$",
    ),
    (
        7,
        _X.PROGRESS,
        r"\b(am i|are we) (close|near|getting|there|on the right|going the right|heading the"
        r" right|far|almost|nearly|in the right|on track|(going|moving|headed|heading) in)\b",
    ),
    (5, _X.PROGRESS, r"\b(almost|nearly) there\b|\bgetting (closer|warmer|colder|further|near)"),
    (5, _X.PROGRESS, r"\b(right|correct) track\b"),
    (5, _X.VISIBILITY, r"\bcan (i|you) see (it|the|them|this)\b|\bdo you see\b"),
    (5, _X.VISIBILITY, r"\b(anywhere|somewhere) (i can see|in sight|visible)\b|\bwhat i see\b"),
    (8, _X.UNKNOWN, r"\byour (favorite|name|age|opinion)\b|\bwho are you\b"),
    (5, _X.VISIBILITY, r"\b(visible|in view|in sight|in my view|on screen|in the (picture|image))"),
)


def _type_of(topic: _Topic) -> QuestionType:
    if isinstance(topic, QuestionType):
        return topic
    if isinstance(topic, RouteKind):
        return QuestionType.ROUTE
    return QuestionType.ATTRIBUTE if isinstance(topic, AttributeTopic) else QuestionType.OTHER


_COMPILED = [(re.compile(pattern), weight, topic) for weight, topic, pattern in _RULES]
# A tie goes to the earlier type: the more specific intent.
_TYPE_ORDER = (_D, QuestionType.ROUTE, QuestionType.OTHER, QuestionType.ATTRIBUTE)


def classify_question(text: str) -> QuestionType:
    """The question type of ``text`` (Attribute, Route, Disambiguation or Other)."""
    return analyse_question(text).question_type


def analyse_question(text: str) -> QuestionAnalysis:
    """Type, topic and mentioned values of a question, by weighted phrase patterns."""
    normalised = _THE_WANTED.sub(r"the target \1", _FILLER.sub("", normalise(text)).strip())
    type_scores = dict.fromkeys(_TYPE_ORDER, 0.0)
    topic_scores: dict[_Topic, float] = {}
    for pattern, weight, topic in _COMPILED:
        if pattern.search(normalised):
            type_scores[_type_of(topic)] += weight
            topic_scores[topic] = topic_scores.get(topic, 0.0) + weight
    best = max(_TYPE_ORDER, key=lambda t: (type_scores[t], -_TYPE_ORDER.index(t)))
    if type_scores[best] == 0.0:
        best = QuestionType.OTHER
    analysis = QuestionAnalysis(
        text=normalised,
        question_type=best,
        yes_no=bool(_YES_NO_START.search(normalised)),
        colors=_mentioned(normalised, list(COLORS)),
        materials=_canonical(_mentioned(normalised, list(_MATERIAL_SYNONYMS)), _MATERIAL_SYNONYMS),
        rooms=_canonical(_mentioned(normalised, list(_ROOM_SYNONYMS)), _ROOM_SYNONYMS),
        this_room=bool(_THIS_ROOM.search(normalised)),
    )
    if best == QuestionType.ROUTE:
        kind = _top([_O, _S, _P], topic_scores)  # ties: the most direct answer
        step = _step_choice(normalised) if kind == RouteKind.STEP else None
        return replace(analysis, route_kind=kind, step_choice=step)
    if best == QuestionType.ATTRIBUTE:
        return replace(analysis, attribute=_top(list(AttributeTopic), topic_scores))
    if best == QuestionType.OTHER:
        other = _top(list(OtherTopic), topic_scores)
        scored = topic_scores.get(other, 0.0) > 0.0
        return replace(analysis, other=other if scored else OtherTopic.UNKNOWN)
    return analysis


_FILLER = re.compile(
    r"^((so|and|ok|okay|well|then|hmm|um|uh|hey|hi|please|sorry|oh|alright|wait|excuse me"
    r"|quick question|one question|a question|question) )+"
    r"|( (please|thanks|thank you|then|now please))+$"
)
# "the chair you want" names the target itself, not an object in view.
_THE_WANTED = re.compile(
    r"\bthe (?!one\b)(\w+) (?:that |which )?(?:you want|you mean|i need|i want|i am looking for"
    r"|we are looking for|you are looking for|i need to find)\b"
)
_THIS_ROOM = re.compile(r"\b(this|same|current) room\b|\broom (i am|we are) in\b")
_TopicT = TypeVar("_TopicT", RouteKind, AttributeTopic, OtherTopic)


def _top(topics: list[_TopicT], scores: dict[_Topic, float]) -> _TopicT:
    """The best-scored topic; a tie goes to the one listed first."""
    return max(topics, key=lambda k: (scores.get(k, 0.0), -topics.index(k)))


def _canonical(words: tuple[str, ...], synonyms: dict[str, str]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(synonyms[w] for w in words))


def _mentioned(text: str, words: list[str]) -> tuple[str, ...]:
    """The words (possibly several tokens long) that occur in ``text``, longest first, each
    occurrence claimed once ("light gray" is not also "gray")."""
    found: list[str] = []
    remaining = f" {text} "
    for word in sorted(words, key=len, reverse=True):
        needle = f" {word} "
        if needle in remaining:
            found.append(word)
            remaining = remaining.replace(needle, " | ")
    return tuple(found)


_SIDE_MOVE = re.compile(r"\b(turn|go|head|move|keep|bear|veer) (to the )?(left|right)\b")
_NOT_A_SIDE = re.compile(r"\bright (here|now|there|way|direction|track|one|place|room)\b")


def _step_choice(text: str) -> StepChoice | None:
    """The action a step question proposes, if it proposes exactly one."""
    if re.search(r"\b(or|either)\b", text):
        return None  # a choice between actions, not a proposal of one
    if re.search(r"\bstop\b", text):
        return StepChoice.STOP
    moves = {m.group(3) for m in _SIDE_MOVE.finditer(text)}
    if not moves:
        sides = _NOT_A_SIDE.sub(" ", text)
        moves = {side for side in ("left", "right") if re.search(rf"\b{side}\b", sides)}
    if len(moves) == 1:
        return StepChoice.LEFT if "left" in moves else StepChoice.RIGHT
    if not moves and re.search(r"\b(forward|straight|ahead|keep going|continue)\b", text):
        return StepChoice.FORWARD
    return None
