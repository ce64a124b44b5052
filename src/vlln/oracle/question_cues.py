"""The topics of a navigator's questions, and the cues for disambiguation ones.

Each cue is a general phrase pattern (a question word with a verb frame, a demonstrative, an
attribute noun, the agent's own state), never a copy of a particular question, so that new
phrasings still meet the cues they share with old ones. The cues read text that
:mod:`vlln.oracle.normalisation` has already cleaned and rephrased; the cues for route
questions are in :mod:`vlln.oracle.route_cues`, those for attribute questions in
:mod:`vlln.oracle.attribute_cues` and those for other questions in
:mod:`vlln.oracle.other_cues`.
"""

from __future__ import annotations

import re
from enum import StrEnum

from vlln.oracle.normalisation import ROOM_SYNONYMS
from vlln.tasks.oracle_protocol import QuestionType


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


Topic = QuestionType | RouteKind | AttributeTopic | OtherTopic
# (weight, topic, pattern): a match adds the weight to the topic and to the topic's type.
Rule = tuple[float, Topic, str]


def alternatives(words: list[str]) -> str:
    """A regex alternation of ``words``, longest first so that "living room" beats "room"."""
    return "|".join(re.escape(w) for w in sorted(words, key=len, reverse=True))


ROOM_WORDS = alternatives([*ROOM_SYNONYMS, "room"])  # every room name a question may use


# The agent itself as a reference point: "in front of me", "in my view".
_DEICTIC = (
    r"\b(in front of|before|next to|near|beside|close to|by|under|beneath) (me|my (feet|camera)"
    r"|the (agent|robot|camera))\b"
    r"|\bcurrently (see|observe|observing|looking at|facing|detecting)\b"
    r"|\b(i am looking at|i am facing|(?<!can )(?<!do )(?<!what )i see|i can see|i found"
    r"|i (just |have just |have )?(found|spotted|detected)|have i found"
    r"|did i find|i spotted|found it|right here|over here|i got it|i am at|i reached"
    r"|have i reached|did i reach|i detected|detected|spotted|observed|candidate|centred"
    r"|centered|in the (center|middle) of (my|the) (view|image|camera|screen|frame))\b"
    r"|\bi am (standing|sitting|pointing|staring|looking|stopped) ((right|just) )?(next to|at"
    r"|in front of|near|beside|by)\b|\bthe \w+ (right )?(here|there)\b"
)
_NOT_WH = r"^(?!(what|which|where|how|why|when)\b).*"  # not a wh-question
_D = QuestionType.DISAMBIGUATION
_TARGETISH = r"(target|goal|one|object|instance|right one|correct one|same one|thing)"
# "the right one", "the goal lamp", "the requested object"
_CHOSEN = (
    r"(right|correct|same|intended|target|goal|requested|specified|described|desired|sought"
    r"|required|mentioned)"
)
_THING = r"(one|object|thing|item|instance)"
_BEARINGS = r"(way|side|direction|turn|track|path|here|now|room)"  # "right way" is no candidate
# "the left branch or the right one" offers two sides, not a candidate.
_NOT_SIDES = r"(?!.*\b(left|right) (\w+ )?or the (left|right) one$)"
# Parts of the way: "the left corridor or the right one" offers two ways, not two candidates.
WAY_PARTS = (
    r"(branch|corridor|hallway|hall|path|way|door|doorway|passage|side|direction|route|turn"
    r"|room|staircase|stairs|exit|opening|fork|gate|entrance|arch|archway|floor)"
)
# "target colour" asks about the target, not whether a candidate is it.
_FACETS = r"(color|material|size|shape|texture|room|location|position|type|category|kind|name)"


# Disambiguation: is what I am looking at the target?
DISAMBIGUATION_RULES: tuple[Rule, ...] = (
    (3, _D, r"^(is|are|was|would) (this|that|these|those)\b"),
    (
        2,
        _D,
        rf"{_NOT_WH}\b(is|are|was) (this|that|these|those)\b"
        r"(?! (way|room|direction|side|place)\b)",
    ),
    (2, _D, rf"\b(this|that) {_THING}\b"),
    (2, _D, r"\b(the|your) one\b"),
    # "the goal object" only names the target; "the right object" weighs a candidate.
    (2, _D, rf"\b(?!(target|goal)\b)({_CHOSEN}|wanted|proper) {_THING}\b"),
    (4, _D, r"\bcandidates?\b|\bbeen (found|located|reached|spotted)\b"),
    (5, _D, r"\bthis (\w+ )?or (that|the other|another|a different|some other)\b"),
    # A choice between two things of one kind: "the red one or the blue one", "this lamp or
    # the one next to it", "the sofa here or the sofa over there"; "is the fridge the silver
    # one or the white one" asks a property of the named target instead.
    (
        6,
        _D,
        rf"^(?!(is|are) the (\w+ )?\w+ the\b)(?!.*\b{WAY_PARTS}\b).*\b(this|that|the) "
        r"((\w+ ){0,3}or (the|that|this) (\w+ )?ones?|(\w+ )?one\b(?! of\b)( \w+){0,4} or"
        r"|(\w+ )?(?P<kind>\w+)\b( \w+){0,3} or (the|that|this) (\w+ )?(?P=kind))\b",
    ),
    (4, _D, r"^(do|did) you mean (this|that|the one|it)\b"),
    # Telegraphic checks and claims: "target?", "is it?", "can i say i found it?"
    (
        4,
        _D,
        r"^(the )?(target|goal|match|is it)$|^is (target|goal)\b"
        r"|^(i )?(found|spotted|located|reached) (it|the|this|that)\b",
    ),
    (
        5,
        _D,
        r"\b(say|declare|claim|call it|report|mark)( that)? (i (have )?found|this (is|as)|it as"
        r"|this one)\b|\b(report|mark|declare|call|count|submit|choose|select|pick|take) (this|that"
        r"|it)( \w+)? as (the |my )?(target|goal|answer|one|right one)\b",
    ),
    # A candidate named and judged in few words: "this chair, target or not?"
    (
        6,
        _D,
        r"^(this|that)( \w+)?( here| there)? (the )?(target|goal|one|correct|right)( one)?( or not"
        r"| yes or no)?$|\b(is|are) (it|this|that) one of the (two|three|several) \w+"
        r"|\b(is|are) (it|this|that) one of (these|those|the) (\w+ )?\w+ (here|there"
        r"|in front of me)$",
    ),
    (4, _D, r"\bthe (\w+ )?one (here|there|right here|over there|in front of me)\b"),
    (4, _D, rf"\b(is|are) (this|that|it) the {_CHOSEN}\b(?! {_BEARINGS}\b)"),
    (
        5,
        _D,
        r"^(could|can|might|would) (this|that|it|the [\w ]+?) be (it|the (one|target|goal|right"
        r"|correct)|the \w+ you)\b"
        r"|^(this|that|it|the)( \w+)*? (could|can|might|may|would|must) be (it|the (one|target"
        r"|goal|right|correct))\b",
    ),
    # "it" as the predicate: "is the thing on the counter it" (not "is the lamp on it").
    (
        8,
        _D,
        r"^(is|are) (the|this|that)( \w+)*?(?<! on)(?<! in)(?<! near)(?<! to)(?<! by)(?<! under)"
        r"(?<! of)(?<! with)(?<! above)(?<! from)(?<! inside)(?<! against)(?<! behind)(?<! beside)"
        r"(?<! below)(?<! at) it$",
    ),
    (2, _D, _DEICTIC),
    # A check after another clause: "should i stop, is this the sofa"
    (
        4,
        _D,
        r"\b(is|are) (this|that|these|those) the (?!.*\b(way|room|direction|side|place|floor"
        rf"|storey|level|house|{ROOM_WORDS})$)(\w+ )?\w+$",
    ),
    (3, _D, r"\b(confirm|verify)\b|\bcheck (if|whether|this|that|it)\b"),
    (4, _D, r"^is it (this|that|these|the one)\b"),
    (
        6,
        _D,
        rf"^{_NOT_SIDES}(is|are|would) (?!there\b)(?!.*\b(as|to|near|from|of|with|by|than|toward"
        r"|under|beside"
        r"|behind|on|in|at|below|above|around) the "
        rf"((right|correct|same|target|intended) )?(target|goal)$).* the ((right|correct|same"
        rf"|target|intended) )?{_TARGETISH}( you \w+( \w+)?)?$",
    ),
    (
        4,
        _D,
        rf"{_NOT_WH}\bis (this|that|it) (the )?(target|goal|one|right one|correct one)\b"
        r"(?! of\b)",
    ),
    (4, _D, rf"^is (it|this|that) the \w+ .*\b({_DEICTIC})"),
    (4, _D, r"^(could|can|might|would) (this|that|it) be (the|it)\b"),
    (3, _D, rf"\bbe (the|it|that|this)( \w+)? {_TARGETISH}\b"),
    (3, _D, r"\b(is|are) (this|that) it\b|\b(this|that) (is|was) (it|the one)\b"),
    (
        4,
        _D,
        r"^(this|that|here|it|this one|that one|here it is|found it|this thing|the one here)"
        r"( here| there| then| now| right| correct| yes)*( or not| yes or no)?$",
    ),
    (
        4,
        _D,
        r"(^|\b(?<!which )(?<!what ))(this|that|here|it)( (?!(or|and|but|like|what|which)\b)"
        r"\w+){0,2} (is|are|was) (it|(the )?"
        r"(right|correct|target|goal|one|same|intended)\b)",
    ),
    (4, _D, r"^(this|that) (is )?(the )?(right|correct|target|same|one)\b"),
    (3, _D, rf"\bis (this|that|it) what you\b|{_NOT_WH}\bis (this|that)( one)?( or not)?$"),
    (
        2,
        _D,
        r"\byou (were |are |have |had )?(want|wanted|mean|meant|described|describing"
        r"|talk(ed|ing) about|think(ing)? of|asked (about|for)|have in mind|look(ed|ing) for)\b",
    ),
    (
        3,
        _D,
        r"^(this|that|these|those) (?!(way|room|direction|side)\b)\w+( (right )?here"
        r"| (over )?there)?( right| correct| yes| or not| then| yes or no)*$",
    ),
    (
        3,
        _D,
        r"\b(am i|i am) (now |currently |already )?((standing|sitting|stopped|right) )?(looking"
        rf"( at)?|(in )?front of|facing|at|beside|next to|by) (it|the {_CHOSEN})\b",
    ),
    # "is the rug in my view the target rug", "is the target the lamp i am pointing at"
    (
        8,
        _D,
        rf"^{_NOT_SIDES}(is|are) (the [\w ]+?|this|that|it) the {_CHOSEN} (?!(color|size|shape"
        r"|material|room"
        r"|way|side|direction)$)\w+$|^(is|are) the (target|goal)( object)? (the|this|that) \w+ "
        r"(i|you|we|on|in|at|by|near|next to|to|here|there|over)\b",
    ),
    (4, _D, rf"^(the )?({_CHOSEN}|wanted) (?!({_BEARINGS}|{_FACETS})\b)\w+$"),
    # The verdict put first: "is correct this lamp", "correct lamp, this?"
    (
        6,
        _D,
        r"^(is|are) (correct|right|the (right|correct|target|same) one) (this|that|it)\b"
        r"|^(the )?(correct|right|target|goal) \w+ (this|that|here)( one)?$",
    ),
    (5, _D, r"^which (one |\w+ )?of (these|those|them|the two|both)\b"),
    # Several candidates in view, then "which one": "i see two chairs, which one is it"
    (
        6,
        _D,
        r"\b(two|three|four|several|multiple|a few|couple of|many|both) (\w+ )?\w+\b[\s\S]*\bwhich"
        r" (one|\w+)( of (them|these|those))? (is|was) (it|the (target|goal|one|right one))\b",
    ),
    # Choosing a candidate: "should i select this lamp", "shall i pick that one".
    (5, _D, r"\b(select|pick|choose|grab|mark|report|settle on) (this|that)( one| \w+)?$"),
    # "which of the plants is the target", "which one is it, the tall lamp or the short lamp"
    (
        6,
        _D,
        r"^which (one )?of (the|these|those|all|both|my) (\w+ )?\w+ (is|are|was) (it|the (target"
        r"|goal|one|right one|correct one))\b|^which (one|\w+) (is it|is the (target"
        r"|goal))\b.* or\b",
    ),
    (5, _D, rf"^which (one )?(is|was) (the )?{_CHOSEN} (one|{_THING})\b"),
    (
        3,
        _D,
        r"\b(did|have) i (find|found|get|got|spot|spotted|reach|reached|arrive at|arrived at"
        r"|locate|located"
        r"|get to|got to) (it|the ((right|correct|target|goal)|\w+ (object|instance)))",
    ),
    (4, _D, rf"{_NOT_WH}\b(is|are|was) the ({_CHOSEN}|target|goal)( one| object)?$"),
    (5, _D, r"^(is|are) (the|my|your) (target|goal)( object)? (this|that|these|those)\b"),
    # Comparing a candidate with the target: "does this match", "does it count as the goal".
    (
        5,
        _D,
        r"\b(match|matches|matching|correspond|corresponds|count as|counts as|identity|identical"
        r"|qualify|qualifies|satisfy|satisfies)\b|\b(fit|fits) (the|your)\b",
    ),
    # "is the one on the left the target", "is the lamp by the door the goal or a distractor"
    (
        5,
        _D,
        r"^(is|are|was) (?!.*\b(near|to|from|of|with|by|than|toward|beside|behind|under|on|in|at"
        r"|as) the (target|goal)\b)(this|that|the|it)\b.* the (target|goal)\b",
    ),
)
