"""The cues that tell a navigator's question types apart: topics and weighted patterns.

Each cue is a general phrase pattern (a question word with a verb frame, a demonstrative, an
attribute noun, the agent's own state), never a copy of a particular question, so that new
phrasings still meet the cues they share with old ones. The cues read text that
:mod:`vlln.oracle.normalisation` has already cleaned and rephrased.
"""

from __future__ import annotations

import re
from enum import StrEnum

from vlln.oracle.normalisation import MATERIAL_SYNONYMS, ROOM_SYNONYMS
from vlln.oracle.protocol import QuestionType
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


Topic = QuestionType | RouteKind | AttributeTopic | OtherTopic


def _alternatives(words: list[str]) -> str:
    return "|".join(re.escape(w) for w in sorted(words, key=len, reverse=True))


_ROOMS = _alternatives([*ROOM_SYNONYMS, "room"])
_COLORS = _alternatives(list(COLORS))
_MATERIALS = _alternatives(list(MATERIAL_SYNONYMS))
_SUPPORTS = r"(floor|ground|wall|table|shelf|counter|desk|cabinet|something)"
_RESTING_ON = r"(on|(sitting|standing|resting|placed|lying|hanging|mounted) on|on top of)"
# The agent itself as a reference point: "in front of me", "in my view".
_DEICTIC = (
    r"(in front of|before|next to|near|beside|close to|by) me\b"
    r"|\bcurrently (see|observe|observing|looking at|facing|detecting)\b"
    r"|\b(i am looking at|i am facing|i see|i can see|i found|i have found|have i found"
    r"|did i find|i spotted|found it|right here|over here|i got it|i am at|i reached"
    r"|have i reached|did i reach|i detected|detected|spotted|observed|candidate)"
    r"|\bi am (standing|sitting|pointing|staring|looking|stopped) (next to|at|in front of|near"
    r"|beside|by)\b"
)
# What surrounds the agent, not the target: "the thing on my left", "what is behind me".
_AROUND_ME = (
    r"((on|to|at) (my|our) (left|right)|(left|right) of (me|us)|(in front of|behind|beside"
    r"|next to|near) (me|us))\b"
)
_NOT_WH = r"^(?!(what|which|where|how|why|when)\b).*"  # not a wh-question
_D = QuestionType.DISAMBIGUATION
_O, _P, _S = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP
_A, _X = AttributeTopic, OtherTopic
_TARGETISH = r"(target|goal|one|object|instance|right one|correct one|same one|thing)"
_CHOSEN = r"(right|correct|same|intended|target|goal)"  # "the right one", "the goal lamp"
_THING = r"(one|object|thing|item|instance)"
_BEARINGS = r"(way|side|direction|turn|track|path|here|now|room)"  # "right way" is no candidate

# (weight, topic, pattern): a match adds the weight to the topic and to the topic's type.
RULES: tuple[tuple[float, Topic, str], ...] = (
    # Disambiguation: is what I am looking at the target?
    (3, _D, r"^(is|are|was|would) (this|that|these|those)\b"),
    (
        2,
        _D,
        rf"{_NOT_WH}\b(is|are|was) (this|that|these|those)\b"
        r"(?! (way|room|direction|side|place)\b)",
    ),
    (2, _D, rf"\b(this|that) {_THING}\b"),
    (2, _D, r"\b(the|your) one\b"),
    (2, _D, rf"\b({_CHOSEN}|wanted|proper) {_THING}\b"),
    (2, _D, _DEICTIC),
    (3, _D, r"\b(confirm|verify)\b|\bcheck (if|whether|this|that|it)\b"),
    (4, _D, r"^is it (this|that|these|the one)\b"),
    (
        6,
        _D,
        r"^(is|are|would) (?!.*\b(as|to|near|from|of|with|by|than|toward) the "
        rf"((right|correct|same|target|intended) )?(target|goal)$).* the ((right|correct|same"
        rf"|target|intended) )?{_TARGETISH}( you \w+( \w+)?)?$",
    ),
    (4, _D, rf"{_NOT_WH}\bis (this|that|it) (the )?(target|goal|one|right one|correct one)\b"),
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
        r"(^|\b(?<!which )(?<!what ))(this|that|here|it)( \w+)?( \w+)? (is|are|was) (it|(the )?"
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
    (3, _D, r"^(this|that|these|those) (?!(way|room|direction|side)\b)\w+( right| correct| yes)?$"),
    (3, _D, rf"\b(am i|i am) (looking( at)?|(in )?front of|facing|at|beside) (it|the {_CHOSEN})\b"),
    # "is the rug in my view the target rug", "is the target the lamp i am pointing at"
    (
        6,
        _D,
        rf"^(is|are) (the [\w ]+?|this|that|it) the {_CHOSEN} (?!(color|size|shape|material|room"
        r"|way|side|direction)$)\w+$|^(is|are) the (target|goal)( object)? (the|this|that) \w+ "
        r"(i|you|we)\b",
    ),
    (4, _D, rf"^(the )?({_CHOSEN}|wanted) (?!{_BEARINGS}\b)\w+$"),
    (3, _D, r"\bdid i (find|get|spot|reach) (it|the (right|correct|target))"),
    # Route, orientation: the direction of the target.
    (4, _O, r"\b(which|what) direction\b"),
    (2, _O, r"\bdirection\b"),
    (3, _O, r"\bwhich (way|side)\b|\bpoint (me|at|to)\b|\b(should i|do i|must i) face\b"),
    (3, _O, r"\b(on|to|at) (my|the|your) (left|right)( side| hand)?+(?! of (it|the|them)\b)"),
    (4, _O, r"\b(left|right) (side |hand )?of me\b|\b(left|right) side or\b"),
    (3, _O, r"(?<!its )(?<!their )\b(left|right) side\b(?! of (it|the|them)\b)"),
    (6, _O, r"\bhow (much|far|many degrees?) (\w+ ){0,3}(turn|rotate)\b|\bturn how much\b"),
    (3, _O, r"\bbehind me\b|\b(in front|ahead) of me or\b|\bwhere to (turn|look|face)\b"),
    (4, _O, r"\b(heading|bearing|angle|orientation|degrees)\b|\bam i facing\b"),
    (2, _O, r"\bface (the|it|them)\b"),
    (5, _O, r"\b(relative|compared) to (me|where i am|my)\b"),
    (4, _O, r"\b(in front|ahead) (of me )?or behind\b|\bbehind (me )?or (in front|ahead)\b"),
    (3, _O, r"^to where\b"),
    (3, _O, r"\b(to|for) see (it|them|the)\b"),
    (3, _O, r"\bin the direction (i am|of)\b|\bwhere (lies|lie)\b|\bin which direction\b"),
    (5, _O, r"\bwhere is (it|the \w+) (from here|from me|relative|compared|in relation)"),
    (
        2,
        _O,
        r"\b(is|are) (it|they|the \w+) ((somewhere|maybe|probably|still) )?"
        r"(ahead|behind|in front|straight|left|right"
        r"|(to|on|at) (the|my|your) (left|right))\b",
    ),
    # Route, path: a way through the house.
    (
        4,
        _P,
        r"\bhow (do |can |should |would |could |shall |must |to |will )?(i |we )?(get|reach|go"
        r"|find|navigate|walk|arrive|head|make it|travel|come)\b",
    ),
    (4, _P, r"\b(route|path|directions|guidance|instructions|navigation|itinerary)\b"),
    (3, _P, r"\bwhere (to|next|now)\b"),
    (
        4,
        _P,
        r"\bwhere (should|do|must|can|shall|could|would|will|to)( (i|we))? (need to |have to "
        r"|want to )?(go|going|head|heading|walk|walking|move|moving|proceed|search|look|explore"
        r"|turn)\b",
    ),
    (3, _P, r"\b(guide|lead|take|show|direct|bring|help|navigate|walk|steer) (me|us)\b"),
    (2, _P, r"\b(get|go) there\b|\bway (to|there|for|toward)\b"),
    (4, _P, r"\b(the|a|best|quickest|shortest|fastest) way (out|to|toward|into|through)\b"),
    (4, _P, r"\bstep by step\b"),
    (4, _P, r"\b(go|walk|head|move|turn) (in order )?(to|for) (get to|reach|arrive)\b"),
    (3, _P, r"\b(pass|cut) through\b|\b(leads?|goes) (to|toward)\b"),
    (3, _P, r"\bfrom (my|our) (current |present )?(position|location|place)\b"),
    (2, _P, r"\b(reaching|arriving|getting to|get to|arrive at|arrive to)\b"),
    (
        5,
        _P,
        r"\bwhich (room|door|doorway|hallway|corridor|exit) (should|do|must|can) (i|we)\b(?! find)",
    ),
    # Route, step: the next action.
    (
        3,
        _S,
        r"\b(should|do|must|shall|can|need) (i|we|to) (need to |have to )?(turn|go|keep|continue"
        r"|stop|move|leave|enter|exit|take|cross|follow|walk|head|proceed|step)\b",
    ),
    (
        3,
        _S,
        r"\b(left or right|right or left|forward or|or forward|straight or|or straight|or back"
        r"|or turn|or stop|or i go)\b",
    ),
    (5, _S, r"\bwhat (should|do|shall|must|can) (i|we) do\b"),
    (5, _S, r"\b(what now|now what|what next|what is next)\b(?! to)"),
    (4, _S, r"\bnext (step|move|movement|action|turn|maneuver)\b|\b(which|what) action\b"),
    (
        3,
        _S,
        r"\b(turn|go|move|head|walk|proceed|step|keep|continue|carry on) (to the )?(left|right"
        r"|forward|straight|back|backward|backwards|ahead|around|on)\b",
    ),
    (2, _S, r"\b(keep going|stop here|go on|continue|turn around|go back)\b"),
    (2, _S, r"^(should|do|shall|must|can) (i|we) .*\b(left|right)\b"),
    (3, _S, r"\b(upstairs|downstairs)\b|^(left|right|straight|forward|back|stop)$"),
    # Attribute: facts about the target.
    (4, _A.COLOR, r"\b(color|colors|colored|hue)\b"),
    (1, _A.COLOR, rf"\b({_COLORS})\b"),
    (
        4,
        _A.MATERIAL,
        r"\b(materials?|composition)\b|\b(made|built|constructed) (of|from|out|with)\b",
    ),
    (4, _A.MATERIAL, r"\bwhat (is|are) (it|they|the \w+) made\b"),
    (1, _A.MATERIAL, rf"\b({_MATERIALS})\b"),
    (
        4,
        _A.TEXTURE,
        r"\b(texture|textured|feel|feels|surface|smooth|rough|soft|glossy|pattern|patterned"
        r"|finish|striped|stripes|spotted|checkered|floral|shiny|matte)\b",
    ),
    (3, _A.DESCRIPTION, r"^(does|do) (it|they|the \w+) have\b|\b(it|the \w+) has\b"),
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
    (5, _A.ROOM, r"^(in|inside) (which|what)\b(?!.*\b(am i|are we|i am|we are)\b)"),
    (5, _A.SUPPORT, r"^(on|on top of|under) (which|what)\b(?! (side|way|direction)\b)"),
    (5, _A.NEARBY, r"^(near|next to|beside|by) (which|what)\b"),
    (4, _A.ROOM, r"\broom (it|they|the \w+( \w+)?) (is|are|sits|stands)( \w+)? in\b"),
    (7, _A.ROOM, r"^(is|are) (it|they|the \w+) in (the|this|my|our|the same|same) room\b"),
    (
        3,
        _A.LOCATION,
        r"^(so |and )?where (\w+ )?(is|are|was) (it|the|they|this|that|your|target)\b",
    ),
    (1, _A.LOCATION, r"^where\b"),
    (
        3,
        _A.LOCATION,
        r"\bwhere (it|they|the \w+( \w+)?) (is|are|hangs|sits|stands|lies|hang|sit|stand)\b",
    ),
    (5, _A.LOCATION, r"\bwhere (can|could|do|would|might|will|should) (i|we) find\b"),
    (3, _A.LOCATION, r"\b(can|could|do|would|might|will|should) (i|we) find (it|the|them)\b"),
    (3, _A.LOCATION, r"\b(located|location|placed|kept|stored|situated|position)\b"),
    (
        3,
        _A.NEARBY,
        r"\b(near|nearby|next to|beside|besides|close to|surrounded|neighbor|neighbors"
        r"|adjacent|surrounding|surroundings|around (it|the|them)|with it|by the)\b(?! me\b)",
    ),
    (
        3,
        _A.NEARBY,
        r"\b(are|is) there (a |an |any |some )?\w+ (on|near|next to|around|beside|by|close to"
        r"|under|above)\b",
    ),
    (3, _A.NEARBY, r"\b(on|to) (its|their) (left|right)\b|\b(left|right)( side)? of (it|the)\b"),
    (6, _A.SUPPORT, rf"\bwhat is (it|the \w+) {_RESTING_ON}\b"),
    (4, _A.SUPPORT, rf"\b{_RESTING_ON} (the|a|top of) {_SUPPORTS}\b"),
    (3, _A.SUPPORT, r"^(is|are) (it|they|the( \w+){1,2}) in (a|an) \w+$"),
    (4, _A.SUPPORT, r"\b(on|in) what$"),
    (2, _A.SUPPORT, r"\b(on top of|under|underneath|below|above|hanging|mounted|against)\b"),
    (
        3,
        _A.SUPPORT,
        rf"^(is|are) (it|they|the \w+) {_RESTING_ON} (the|a|an|some|top of) "
        r"(?!(left|right|way|other)\b)",
    ),
    (
        5,
        _A.CATEGORY,
        r"\b(what|which) (kind|type|sort|style|model|brand)\b|\b(category|categories)\b",
    ),
    (3, _A.CATEGORY, r"\b(style|design|model|brand|kind|type)\b"),
    (
        3,
        _A.CATEGORY,
        r"^what (is|are) (it|they|the (target|goal)( object)?|the object)$|\bwhat exactly\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\b(describe|description|appearance|details|detail|features|characteristics"
        r"|distinctive|distinguishing|special|unique|identify|recognize|distinguish|mark"
        r"|marks|markings)\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\blooks? like\b|\btell me (more |something |anything |everything )?about\b"
        r"|\b(what|everything|anything|all) you know\b|\bstands? out\b",
    ),
    (3, _A.DESCRIPTION, r"\b(anything|something|what) else\b|\babout (it|the (target|goal))\b"),
    (4, _A.DESCRIPTION, r"\bhow ((is|are|does|do|did) )?((it|they|the \w+) )?looks?\b"),
    (5, _A.DESCRIPTION, r"\bwhat (object|thing|item) (am i|are we|should i|do i|must i)\b"),
    (
        4,
        _A.DESCRIPTION,
        r"\b(more|any|some|other|a|another) (info|information|hints?|clues?|details)\b",
    ),
    (5, _A.DESCRIPTION, r"\bwhat (am i|are we|are you|\w+ (i|we)( be)?) (look|search)(ing)? for\b"),
    (6, _A.DESCRIPTION, r"\bwhat (does|do|did) (it|they|the \w+) (show|depict|display|say|read)\b"),
    (6, _A.DESCRIPTION, r"\b(shown|depicted|displayed|painted|printed|written) (in|on)\b"),
    (
        4,
        _A.DESCRIPTION,
        r"\bwhich (one|\w+)(?<!side)(?<!way)(?<!direction) (is it|is the (target|goal|one)"
        r"|do you mean|are you looking for|should i find|am i looking)\b",
    ),
    # Other: what privileged knowledge of the agent's state answers.
    (
        7,
        _X.AGENT_ROOM,
        r"\b(which|what) (room|part of the house|area|place) (am i|are we|is this|is here)",
    ),
    (
        7,
        _X.AGENT_ROOM,
        rf"\bwhere am i\b|\bwhere are we\b(?! (going|headed|heading))"
        rf"|^(is this|is that|are we in|is here|is this room|is this place) (the |a )?({_ROOMS})$",
    ),
    (6, _X.AGENT_ROOM, r"\b(am i|are we) in (the|a|an)\b"),
    (8, _X.AGENT_ROOM, r"\b(room|place) (i|we) (am|are) (\w+ ){0,2}in\b"),
    (
        8,
        _X.AGENT_ROOM,
        r"(?<!from )(?<!to )\b(my|our) (current |present )?(location|position|room|whereabouts)\b",
    ),
    (
        7,
        _X.DISTANCE,
        r"\bhow (far|close|near|long|many (steps?|meters?|feet|moves?|more)|much (further"
        r"|farther|longer|more|far))\b",
    ),
    (4, _X.DISTANCE, r"\b(distance|far away|how far)\b|^far$"),
    (
        7,
        _X.DISTANCE,
        r"\bis (it|the \w+) (still |very )?(far|close|near|nearby)( from here| away)?$",
    ),
    (
        7,
        _X.PROGRESS,
        r"\b(am i|are we|i am|we are) ((anywhere|still|now|already|even|really) )?(close|near"
        r"|getting|there|on the right|on the correct|going the right|heading the right|far"
        r"|almost|nearly|in the right|on track|(going|moving|headed|heading) in)\b",
    ),
    (5, _X.PROGRESS, r"\b(almost|nearly) (there|done|finished)\b|\bgetting (closer|warmer|colder)"),
    (5, _X.PROGRESS, r"\bgetting (further|near)|\b(right|correct) track\b|\bclose or far\b"),
    (6, _X.PROGRESS, r"\b(have|did) (i|we) (already )?(been|visit|visited|search|searched|check)"),
    (5, _X.VISIBILITY, r"\bcan (i|you) see (it|the|them|this)\b|\bdo you see\b"),
    (5, _X.VISIBILITY, r"\b(anywhere|somewhere) (i can see|in sight|visible)\b|\bwhat i see\b"),
    (8, _X.UNKNOWN, r"\byour (favorite|name|age|opinion)\b|\bwho are you\b|\byourself\b"),
    # The agent's surroundings and past, the house as a whole, the oracle itself.
    (8, _X.UNKNOWN, rf"^(what|which \w+) (is|are) (\w+ ){{0,3}}{_AROUND_ME}"),
    (4, _X.UNKNOWN, rf"^(?!(is|are)\b).*\b(thing|object|item|stuff) (\w+ )?{_AROUND_ME}"),
    (6, _X.UNKNOWN, r"\bwhat (is|are) (this|that|these|those)\b(?! (room|place|\w+ you)\b)"),
    (
        8,
        _X.UNKNOWN,
        r"\b(which|what) (room|rooms|place|area) ((did|have|had|was|were) (i|we)|(i|we) (came"
        r"|come|was|were|visited|have))\b|\b(came|come) from\b",
    ),
    (
        9,
        _X.UNKNOWN,
        r"^(is|how (big|large|small|old|many \w+) is) (the|this|that|whole|your) (house|home"
        r"|apartment|flat|building)\b|^(house|home|apartment) \w+$",
    ),
    (6, _X.UNKNOWN, r"^why\b|^((can|could|would|will) you )?help( me| us)?( out| please)*$"),
    (8, _X.UNKNOWN, r"\bhow (do|did|can|could|would) you (know|tell(?! me)|be sure|remember)\b"),
    (6, _X.UNKNOWN, r"^what (is|else is|objects are|things are) in (this|the current|my) room$"),
    (5, _X.VISIBILITY, r"\b(visible|in view|in sight|in my view|on screen|in the (picture|image))"),
)
