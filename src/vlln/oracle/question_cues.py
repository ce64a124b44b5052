"""The topics of a navigator's questions, and the cues for disambiguation and route ones.

Each cue is a general phrase pattern (a question word with a verb frame, a demonstrative, an
attribute noun, the agent's own state), never a copy of a particular question, so that new
phrasings still meet the cues they share with old ones. The cues read text that
:mod:`vlln.oracle.normalisation` has already cleaned and rephrased; the cues for attribute
questions are in :mod:`vlln.oracle.attribute_cues`, those for other questions in
:mod:`vlln.oracle.other_cues`.
"""

from __future__ import annotations

import re
from enum import StrEnum

from vlln.oracle.normalisation import ROOM_SYNONYMS
from vlln.oracle.protocol import QuestionType


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
    r"|centered|in the (center|middle) of (my|the) (view|image|camera|screen|frame))"
    r"|\bi am (standing|sitting|pointing|staring|looking|stopped) ((right|just) )?(next to|at"
    r"|in front of|near|beside|by)\b|\bthe \w+ (right )?(here|there)\b"
)
_NOT_WH = r"^(?!(what|which|where|how|why|when)\b).*"  # not a wh-question
_D = QuestionType.DISAMBIGUATION
_O, _P, _S = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP
_TARGETISH = r"(target|goal|one|object|instance|right one|correct one|same one|thing)"
# "the right one", "the goal lamp", "the requested object"
_CHOSEN = (
    r"(right|correct|same|intended|target|goal|requested|specified|described|desired|sought"
    r"|required|mentioned)"
)
_THING = r"(one|object|thing|item|instance)"
_BEARINGS = r"(way|side|direction|turn|track|path|here|now|room)"  # "right way" is no candidate
# "the right side table" names a thing, not a side.
_SIDE_THINGS = r"(side )?(table|tables|board|boards|door|doors|drawer|lamp|cabinet)\b"
# "the left branch or the right one" offers two sides, not a candidate.
_NOT_SIDES = r"(?!.*\b(left|right) (\w+ )?or the (left|right) one$)"
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
        r"|this one)\b",
    ),
    (4, _D, r"\bthe (\w+ )?one (here|there|right here|over there|in front of me)\b"),
    (4, _D, rf"\b(is|are) (this|that|it) the {_CHOSEN}\b(?! {_BEARINGS}\b)"),
    (
        5,
        _D,
        r"^(could|can|might|would) (this|that|it|the [\w ]+?) be (it|the (one|target|goal|right"
        r"|correct)|the \w+ you)\b",
    ),
    (2, _D, _DEICTIC),
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
        rf"( at)?|(in )?front of|facing|at|beside) (it|the {_CHOSEN})\b",
    ),
    # "is the rug in my view the target rug", "is the target the lamp i am pointing at"
    (
        6,
        _D,
        rf"^{_NOT_SIDES}(is|are) (the [\w ]+?|this|that|it) the {_CHOSEN} (?!(color|size|shape"
        r"|material|room"
        r"|way|side|direction)$)\w+$|^(is|are) the (target|goal)( object)? (the|this|that) \w+ "
        r"(i|you|we)\b",
    ),
    (4, _D, rf"^(the )?({_CHOSEN}|wanted) (?!({_BEARINGS}|{_FACETS})\b)\w+$"),
    (5, _D, r"^which (one |\w+ )?of (these|those|them|the two|both)\b"),
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
ROUTE_RULES: tuple[Rule, ...] = (
    # Route, orientation: the direction of the target.
    (4, _O, r"\b(which|what) direction\b"),
    (2, _O, r"\bdirection\b"),
    (
        3,
        _O,
        r"\bwhich (way|side)\b|\bwhat side\b|\bpoint (me|at|to)\b"
        r"|\b(should i|do i|must i) (be )?(face|facing)\b|\b(north|south|east|west)\b",
    ),
    (
        3,
        _O,
        r"\b(on|to|at) (my|the|your) (left|right)( side| hand)?+(?! of (it|the|them)\b)"
        rf"(?! {_SIDE_THINGS})",
    ),
    (4, _O, r"\b(left|right) (side |hand )?of me\b|\b(left|right) side or\b"),
    (
        3,
        _O,
        r"^(?!.*\b(left|right) side of (it|the|a|an|them)\b).*(?<!its )(?<!their )"
        rf"\b(left|right) side\b(?! of (it|the|them)\b)(?! {_SIDE_THINGS})",
    ),
    (2, _O, r"\bmy (left|right)\b"),
    (
        3,
        _O,
        r"\b(more|further|slightly|bit|little) ((to|toward) )?((the|my) )?(left|right)\b",
    ),
    (6, _O, r"\b(left|right) (\w+ )?or the (left|right) one\b"),
    (
        3,
        _O,
        r"^(is|are) (it|they|the (\w+ )?\w+) ((straight|right|directly|somewhere) )?(in front of"
        r"|behind|ahead of|to the (left|right) of|on the (left|right) of) (me|us)"
        r"( right now| now| currently)?$",
    ),
    (6, _O, r"\bhow (much|far|many degrees?) (\w+ ){0,4}(turn|rotate)\b|\bturn how much\b"),
    (
        3,
        _O,
        r"\bbehind me\b|\b(in front|ahead) of me or\b|\bwhere to (turn|look|face)\b"
        r"|\b(behind|in|at) my back\b|\bto the front of me\b",
    ),
    (
        4,
        _O,
        r"\b(heading|bearing|angle|orientation|degrees|azimuth|clockwise|counterclockwise"
        r"|anticlockwise|egocentric)\b|\bam i facing\b"
        r"|\b(am i|i am) (turned|pointed|pointing|oriented|aligned|facing) (toward|to|at)\b",
    ),
    (
        4,
        _O,
        r"\b(to|on) the (left|right) or (to |on )?(the )?(left|right)\b"
        r"(?!( side| hand side)? of (it|its|the|a|an|their)\b)",
    ),
    (2, _O, r"\bface (the|it|them)\b"),
    (4, _O, r"\b(yaw|rotation)\b"),
    (5, _O, r"\b(relative|compared) to (me|where i am|my)\b"),
    (4, _O, r"\b(in front|ahead) (of me )?or behind\b|\bbehind (me )?or (in front|ahead)\b"),
    (3, _O, r"^to where\b"),
    (3, _O, r"\b(to|for) see (it|them|the)\b"),
    (3, _O, r"\bin the direction (i am|of)\b|\bwhere (lies|lie)\b|\bin which direction\b"),
    (
        5,
        _O,
        r"\bwhere is (it|the \w+) (from here|from me|from my|relative|compared|in relation)"
        r"|\bfrom my (point of view|perspective|viewpoint|position)\b|\bo ?clock\b",
    ),
    (
        2,
        _O,
        r"\b(is|are) (it|they|the \w+) ((somewhere|maybe|probably|still) )?"
        r"(ahead|behind|in front|straight|left|right"
        r"|(to|on|at) (the|my|your) (left|right))\b(?!( side| hand)? of (it|the|a|an|them)\b)",
    ),
    # Route, path: a way through the house.
    (
        4,
        _P,
        r"\bhow (do |does |can |should |would |could |shall |must |to |will |might |may )?"
        r"(i |we |one )?(to )?"
        r"(get|reach|go"
        r"|find|navigate|walk|arrive|head|make it|travel|come|proceed)\b",
    ),
    (4, _P, r"\b(route|path|directions|guidance|instructions|navigation|itinerary)\b"),
    (3, _P, r"\bthe (road|way) to\b|\b(go|get|reach|walk|head) (to|there)\b.*\bhow$"),
    (3, _P, r"\bwhere (to|next|now)\b"),
    (
        4,
        _P,
        r"\bwhere (should|do|must|can|shall|could|would|will|to)( (i|we|you))? (need to |have to "
        r"|want to )?(go|going|head|heading|walk|walking|move|moving|proceed|search|look|explore"
        r"|turn)\b",
    ),
    (3, _P, r"\b(guide|lead|take|show|direct|bring|help|navigate|walk|steer) (me|us)\b"),
    (2, _P, r"\b(get|go) there\b|\bway (to|there|for|toward)\b"),
    (4, _P, r"\b(the|a|best|quickest|shortest|fastest) way (out|to|toward|into|through)\b"),
    (4, _P, r"\bstep by step\b"),
    (4, _P, r"\bwhich way (do i go |should i go |to go )?(to|toward|into) (the|a|my)\b"),
    (4, _P, r"\bbetween (me|here|us) and\b|\brooms? (\w+ )?(lie|lies|are|is) between\b"),
    (3, _P, r"\bfrom (the |my |this |here )(\w+ ){0,3}to (the|my|your|its|a|that) "),
    (4, _P, r"\b(which|what) (room|door|hallway|corridor) (next|now|first|then)\b|\bthen where\b"),
    (4, _P, r"\b(tell|show|give|explain|describe)( me| us)? (the|a) way\b"),
    (3, _P, r"\b(plan|planning|chart|map out)\b"),
    (4, _P, r"\b(go|walk|head|move|turn) (in order )?(to|for) (get to|reach|arrive)\b"),
    (3, _P, r"\b(pass|cut) through\b|\b(leads?|goes) (to|toward)\b|\btraverse\b"),
    (4, _P, r"\b(which|what) rooms?\b.*\b(through|pass|cross|traverse)\b"),
    (2, _P, r"\bto reach (it|the|that|my)\b"),
    (3, _P, r"\bfrom (my|our) (current |present )?(position|location|place)\b"),
    (2, _P, r"\b(reaching|arriving|getting to|get to|arrive at|arrive to)\b"),
    (
        5,
        _P,
        rf"\bwhich (room|door|doorway|hallway|corridor|exit|{ROOM_WORDS}) (should|do|must|can)"
        r" (i|we)\b(?! find)",
    ),
    # Route, step: the next action.
    (
        3,
        _S,
        r"\b(should|do|must|shall|can|need) (i|we|to) (need to |have to )?(turn|go|keep|continue"
        r"|stop|move|leave|enter|exit|take|cross|follow|walk|head|proceed|step|approach|advance"
        r"|back up|back off|rotate|climb|wait|stay|carry on)\b"
        r"(?! (a|an|some) (break|rest|nap|pause|breather)\b)",
    ),
    (
        3,
        _S,
        r"\b(left or right|right or left|forward or|or forward|straight or|or straight|or back"
        r"|or turn|or stop|or i go)\b",
    ),
    (
        5,
        _S,
        r"\bwhat (\w+ ){0,4}?((should|do|shall|must|can|would) (i|we|you)|(i|we) (should|must"
        r"|can|need to|have to)) do\b(?!.*\b(when|once|after|if) (i|we) find\b)",
    ),
    (4, _S, r"\b(up|down|in|out|forward|ahead|straight|back|upstairs|downstairs) or not\b"),
    (4, _S, r"\btime to (stop|turn|go|move|leave|enter|head)\b"),
    (5, _S, r"\b(what now|now what|what next|what is next)\b(?! to)"),
    (4, _S, r"\bnext (step|move|movement|action|turn|maneuver)\b|\b(which|what) action\b"),
    (
        3,
        _S,
        r"\b(turn|turning|go|going|move|moving|head|heading|walk|walking|proceed|step|keep|continue"
        r"|carry on) (to the )?(left|right|forward|straight|back|backward|backwards|ahead|around"
        r"|(?<!turn )(?<!turning )on)\b",
    ),
    (3, _S, r"\b(go|walk|step|head|move) (in|inside|into|out|up|down)\b"),
    (2, _S, r"\b(keep going|stop here|go on|continue|turn around|go back)\b"),
    (3, _S, r"\b(right|correct|best|next|good) (move|action|choice|maneuver)\b"),
    (2, _S, r"^(should|do|shall|must|can) (i|we) .*\b(left|right)\b"),
    (2, _S, r"\b(upstairs|downstairs)\b"),
    # Bare actions: "turn?", "straight on?", "forward, left, right or stop?"
    (
        4,
        _S,
        r"^((turn|go|keep) )?(left|right|straight|forward|back|stop|turn|next|action|move|continue"
        r"|carry on|proceed|straight on|keep going)$|\b(forward|straight|ahead)\b.*\b(left|right)"
        r"\b.*\b(stop|left|right)\b",
    ),
)
