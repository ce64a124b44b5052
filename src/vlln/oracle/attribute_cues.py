"""The cues for attribute questions: a property of the target or of its place.

Colour, material, texture, shape, size, kind, the room it is in, what it stands on and what
is near it. Like :mod:`vlln.oracle.question_cues`, they read normalised, rephrased text.
"""

from __future__ import annotations

from vlln.oracle.normalisation import MATERIAL_SYNONYMS
from vlln.oracle.question_cues import ROOM_WORDS, AttributeTopic, Rule, alternatives
from vlln.world.materials import COLORS

_COLORS = alternatives(list(COLORS))
_MATERIALS = alternatives(list(MATERIAL_SYNONYMS))
# What an object can stand, lie or hang on.
_SUPPORTS = (  # also the last word of a joined name: "coffee_table"
    r"(\w+_)?(floor|ground|wall|table|shelf|counter|desk|cabinet|something|bed|sofa|couch|chair"
    r"|stool"
    r"|dresser|nightstand|windowsill|sill|ledge|stand|rack|bench|mantel|mantelpiece|island"
    r"|carpet|rug|tray|wardrobe|bookshelf|armchair|ottoman|fireplace)"
)
_RESTING_ON = (
    r"(on|upon|(sit|sits|sitting|stand|stands|standing|rest|rests|resting|placed|lie|lies|lying"
    r"|hang|hangs|hanging|mounted|leaning|leans|lean) (on|upon)|on top of)"
)
# A storey of the house, not a floor something stands on: "on the same floor as me".
_STOREY = (
    r"(same|this|current|ground|upper|lower|top|first|second|other|another|next) floor\b"
    r"(?! (lamp|lamps|mat|rug|cushion|tiles?|boards?)\b)"  # "this floor lamp" is an object
)
# Words that make "x or y" a choice of way, distance or candidate, not of a property.
_NOT_PROPERTIES = (
    r"(left|right|straight|forward|backward|backwards|back|behind|ahead|front|near|far|close"
    r"|closer|farther|further|up|down|upstairs|downstairs|in|on|out|inside|outside|here|there"
    r"|elsewhere|stop|turn|go|wait|continue|keep|now|later|not|no|yes|either|neither|both|and"
    r"|this|that|the|a|an|it|one|ones|other|another|else|something|anything|nothing|i|me|you"
    r"|we|us|what|which|where|how|is|are|am|should|do|did|can|must|floor|room|door|doorway"
    rf"|\w+_(room|door)|{ROOM_WORDS})"
)
_A = AttributeTopic

# Attribute: facts about the target.
ATTRIBUTE_RULES: tuple[Rule, ...] = (
    (4, _A.COLOR, r"\b(color|colors|colored|hue)\b|\b(shade|tone|tint) of\b|\bwhat (shade|tone)\b"),
    (1, _A.COLOR, rf"\b({_COLORS})\b"),
    (
        4,
        _A.MATERIAL,
        r"\b(materials?|composition|upholstery|upholstered)\b|\b(made|built|constructed) (of|from"
        r"|out|with)\b",
    ),
    (4, _A.MATERIAL, r"\bwhat (is|are) (it|they|the (\w+ )?\w+) made\b"),
    (1, _A.MATERIAL, rf"\b({_MATERIALS})\b"),
    (
        4,
        _A.TEXTURE,
        r"\b(texture|textured|feel|feels|surface|smooth|rough|soft|glossy|pattern|patterned"
        r"|striped|stripes|spotted|checkered|floral|shiny|matte)\b"
        r"|(?<!to )\bfinish\b(?! (this|the|my|it)\b)",
    ),
    (
        3,
        _A.DESCRIPTION,
        r"^(does|do) (it|they|the (\w+ )?\w+) have\b|\b(it|they|the (\w+ )?\w+) (has|have|got)\b",
    ),
    (2, _A.CATEGORY, r"\b(is|are) (it|they|the (\w+ )?\w+) (a|an) "),
    (4, _A.SHAPE, r"\b(shape|shaped|form|round|square|rectangular|oval|circular)\b"),
    (5, _A.SIZE, r"\bhow (big|large|small|tall|high|wide|long|heavy)\b"),
    (
        3,
        _A.SIZE,
        r"\b(size|sized|dimensions|height|width|bigger|larger|smaller|big|large|small|tall|heavy"
        r"|weigh|weighs|weight)\b"
        r"|\b(taller|shorter|wider|higher|longer|heavier|lower|thicker|thinner) than\b",
    ),
    (
        8,
        _A.SIZE,
        r"\bhow (long|tall|wide|high|deep) (is|are) (it|they|the (?!(path|route|way|walk|trip"
        r"|journey|distance)\b)\w+)\b",
    ),
    (
        4,
        _A.ROOM,
        rf"\b(which|what) (room|part of the house|area|region|{ROOM_WORDS})\b(?! (leads?|goes"
        r"|connects|(should|do|must|can) (i|we)|am i|are we)\b)|\bsame room\b",
    ),
    (3, _A.ROOM, rf"\bin (the|a|an|this|my|our|that|same) (\w+ )?({ROOM_WORDS})\b"),
    (5, _A.ROOM, r"^(in|inside) (which|what)\b(?!.*\b(am i|are we|i am|we are)\b)"),
    (5, _A.SUPPORT, r"^(on|on top of|under) (which|what)\b(?! (side|way|direction)\b)"),
    (5, _A.ROOM, r"^(the )?(room|location|position|place|whereabouts) of (the|it|this|that)\b"),
    (5, _A.NEARBY, r"^(near|next to|beside|by) (which|what)\b"),
    (4, _A.ROOM, r"\broom (it|they|the \w+( \w+)?) (is|are|sits|stands)( \w+)? in\b"),
    (
        7,
        _A.ROOM,
        r"^(is|are) (it|they|the (\w+ )?(?!(on|off|open|closed|still)\b)\w+) in (the|this|my|our"
        r"|the same|same) room\b",
    ),
    (
        3,
        _A.LOCATION,
        r"\bwhere (\w+ )?(is|are|was) (it|the|they|this|that|your|target)\b",
    ),
    (1, _A.LOCATION, r"^where\b"),
    (
        3,
        _A.LOCATION,
        r"\bwhere (it|they|the \w+( \w+)?) (is|are|hangs|sits|stands|lies|hang|sit|stand)\b",
    ),
    (5, _A.LOCATION, r"\bwhere (can|could|do|would|might|will|should) (i|we) find\b"),
    (7, _A.LOCATION, r"\b(which|what) floor (is|are) (it|they|the (\w+ )?\w+) (on|located)\b"),
    (3, _A.LOCATION, r"\b(can|could|do|would|might|will|should) (i|we) find (it|the|them)\b"),
    (
        3,
        _A.LOCATION,
        r"\b(located|location|placed|kept|stored|situated|position|resides|reside)\b",
    ),
    (
        5,
        _A.ROOM,
        r"\bin (which|what) (\w+ )?(room|chamber|part|area|place)\b"
        r"(?!.*\b(am i|are we|i am|we are)\b)",
    ),
    (
        3,
        _A.LOCATION,
        r"^(is|are) (it|they|the (\w+ )?\w+) .*\b(upstairs|downstairs|(ground|upper|top|first"
        r"|second) floor)\b",
    ),
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
        r"|under|above|in front of|behind|against|opposite)\b",
    ),
    (3, _A.NEARBY, r"\b(on|to) (its|their) (left|right)\b"),
    (10, _A.NEARBY, r"\b(left|right)( side| hand side)? of (it|its|the (?!room\b)|a|an|their)\b"),
    (
        6,
        _A.DESCRIPTION,
        r"\bhow many \w+ ((does|do|did) (it|they|the (\w+ )?\w+) have|(has|have) (it|they|the"
        r" (\w+ )?\w+))\b"
        r"|(?<!view )(?<!image )(?<!camera )(?<!frame )\bcontain(s|ing)?\b"
        r"|\bwhat (it|they|the (\w+ )?\w+) (contains|holds|shows|says|depicts|displays"
        r"|represents)\b",
    ),
    (
        4,
        _A.NEARBY,
        r"\bwhat (\w+ )?(is|are) (on|in|inside|around|near|next to|beside|under|above|behind"
        r"|against) (it|them|the (\w+ )?\w+)$",
    ),
    (6, _A.SUPPORT, rf"\bwhat is (it|the \w+) {_RESTING_ON}\b"),
    (4, _A.SUPPORT, rf"\b{_RESTING_ON} (the|a|an|top of) (?!{_STOREY})(\w+ )?{_SUPPORTS}\b"),
    (
        5,
        _A.NEARBY,
        r"\bwhat (is|are|lies|lie|sits|stands|hangs) (\w+ )?(beneath|under|underneath|below|above"
        r"|on top of|next to|beside|behind|near|around|in front of) (it|the)\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\bwhat (is|are) (inside (it|them|the)|(in|on) (it|them|the (target|goal)))\b",
    ),
    (5, _A.NEARBY, r"\b(which|what) side of (the|it|its|them)\b"),
    # The relation asked for at the end: "what is the sofa facing", "what is it beside".
    (
        6,
        _A.NEARBY,
        r"\bwhat (is|are) (it|they|the (\w+ )?\w+) (facing|beside|next to|near|by|behind|close to"
        r"|against|in front of|opposite|across from)\b",
    ),
    # A guess at its place: "would the plant be on the windowsill", "might it be in a drawer".
    (
        5,
        _A.LOCATION,
        r"^(would|could|might|will|should|can) (it|they|the [\w ]+?) be (on|in|inside|near|next to"
        r"|by|under|above|beside|against|on top of|somewhere)\b",
    ),
    (3, _A.SUPPORT, r"^(is|are) (it|they|the( \w+){1,2}) in (a|an) \w+$"),
    (4, _A.SUPPORT, r"\b(on|in) what$|\b(supports?|supporting|holds? up)\b"),
    (
        2,
        _A.SUPPORT,
        r"\b(on top of|under|underneath|below|above|hanging|mounted|against|attached|fixed"
        r"|leaning|hung)\b",
    ),
    (
        4,
        _A.NEARBY,
        r"^(?!.*\b(am i|are we|i am|we are)\b).*\bwithin (\w+ ){0,3}(of|from) (it|the)\b",
    ),
    (
        3,
        _A.SUPPORT,
        rf"^(is|are) (it|they|the (\w+ )?\w+) {_RESTING_ON} (the|a|an|some|top of) "
        rf"(?!(left|right|way|other)\b|{_STOREY})",
    ),
    (
        5,
        _A.CATEGORY,
        r"\b(what|which) (kind|type|sort|style|model|brand)\b|\b(category|categories)\b",
    ),
    (
        3,
        _A.CATEGORY,
        r"\b(style|design|model|brand|kind|type)\b|\bone of (those|these|the)\b|\bsort of \w+",
    ),
    # A yes/no question about a named object, with no other cue, is most likely about the
    # target's properties ("is the candle lit", "is the kettle electric or not").
    (
        1,
        _A.DESCRIPTION,
        r"^(is|are|was|does|do) (it (\w+ ){0,2}?or|the (\w+ ){0,2}?\w+ (?!(not|there)\b)\w+)",
    ),
    # Commands that name a fact: "report the colour of the target", "return the room label".
    (
        4,
        _A.DESCRIPTION,
        r"^(report|return|give|state|provide|output|name|specify|list|enumerate|identify|tell me)"
        r" (me )?(the |its |a )?((target|goal|object|instance)s? )?(room|color|material|size"
        r"|shape|texture|category|type|height|width|length|finish|pattern|name|label|objects?"
        r"|surface|features)\b",
    ),
    (
        3,
        _A.ROOM,
        r"^(report|return|give|state|provide|output|name|specify|tell me) (me )?(the )?room\b",
    ),
    (
        5,
        _A.SUPPORT,
        rf"^(?!(which|what) (side|way|direction)\b).*\b(it|they|the (\w+ )?\w+) {_RESTING_ON}$",
    ),
    (
        4,
        _A.NEARBY,
        r"\b(closest|nearest) (\w+ )?(to (it|the|them)|object|thing|item|furniture|landmarks?)\b",
    ),
    (
        3,
        _A.CATEGORY,
        r"^what (is|are) (it|they|the (target|goal)( object)?|the object)( exactly| again)?$"
        r"|\bwhat exactly\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\b(describe|description|appearance|details|detail|features|characteristics"
        r"|distinctive|distinguishing|special|unique|identify|recognize|distinguish|mark"
        r"|marks|markings|differs|differ)\b|\bdifferent from\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\blooks? like\b|\btell me (more |something |anything |everything )?about\b"
        r"|\b(what|everything|anything|all) you know\b|\bstands? out\b",
    ),
    (3, _A.DESCRIPTION, r"\b(anything|something|what) else\b|\babout (it|the (target|goal))\b"),
    (4, _A.DESCRIPTION, r"^what (is|are) (it|they|the (\w+ ){0,3}?\w+) like$"),
    (3, _A.DESCRIPTION, r"\bthe (\w+ )?one with\b|\b(full|empty|filled)\b"),
    (4, _A.LOCATION, r"\b(holds|contains|has) the (target|goal)\b"),
    (
        5,
        _A.LOCATION,
        r"\b(which|what) (corner|part|side|end|area|wall|spot) of the (room|house|\w+)\b"
        r"(?!.*\b(am i|are we)\b)",
    ),
    (
        3,
        _A.NEARBY,
        r"\b(spatial|relationship)\b|\brelation\b(?!( to (me|us|where i am|my \w+))?$)",
    ),
    # Parts and contents: "are there flowers in the vase", "has frame the picture".
    (
        4,
        _A.DESCRIPTION,
        r"^(are|is) there (a |an |any |some )?(\w+ )?\w+ (in|inside|within) (it|them|the "
        rf"(?!(house|home|{ROOM_WORDS})\b)(\w+ )?\w+)$|^what (is|are) (it|they|the (\w+ )?\w+)"
        r" (of|about)$",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"^(has|have) (a |an |any |some )?\w+ (the|it|this|that)\b|^(has|have) (it|they|the (\w+"
        r" )?\w+) (got )?(a|an|any|some)\b",
    ),
    # A part stated for confirmation: "wardrobe has mirror on the door?"
    (
        3,
        _A.DESCRIPTION,
        r"^(?!(i|you|we|he|she|who|what|which|where|how|there|here|do|does|did)\b)(the |this "
        r"|that )?(\w+ )?"
        r"\w+ (has|have) (a |an |any |some |no )?(?!(been|to|got to)\b)\w+",
    ),
    # What the target itself does: "does it stand on four legs", "does the chair swivel".
    (
        2,
        _A.DESCRIPTION,
        r"^(does|do|did) (it|they|the (\w+ )?\w+) (?!(matter|mean|count|match|help|make"
        r"|look)\b)\w+",
    ),
    # A bare noun stated with a property: "candle is lit?", "sofa is red?"
    (
        2,
        _A.DESCRIPTION,
        r"^(?!(i|you|we|it|this|that|there|here|which|what|where|how|who|one|everything|still|now"
        r"|so|then|also|maybe)\b)(the )?\w+ (is|are) (?!(it|the|a|an|this|that|there|here|on|in|at"
        r"|to|my|your|far|near|close|nearby)\b)\w+$",
    ),
    # A choice between two values of a property: "digital or analog", "single or double".
    (
        2,
        _A.DESCRIPTION,
        rf"\b(?!{_NOT_PROPERTIES}\b)\w+ or (a |an )?(?!{_NOT_PROPERTIES}\b)\w+\b",
    ),
    (
        4,
        _A.DESCRIPTION,
        r"\bhow (\w+ )?((is|are|does|do|did) )?((it|they|the (\w+ )?\w+) )?look(s|ing)?\b",
    ),
    (5, _A.DESCRIPTION, r"\bwhat (object|thing|item) (am i|are we|should i|do i|must i)\b"),
    (
        4,
        _A.DESCRIPTION,
        r"\b(more|any|some|other|a|another) (info|information|hints?|clues?|details)\b",
    ),
    (5, _A.DESCRIPTION, r"\bwhat (am i|are we|are you|\w+ (i|we)( be)?) (look|search)(ing)? for\b"),
    (
        6,
        _A.DESCRIPTION,
        r"\bwhat (does|do|did) (it|they|the (\w+ )?\w+) (show|depict|display|say|read|hold"
        r"|contain|represent|portray|illustrate)\b|\bwhat (is|are) (it|they|the (\w+ )?\w+) "
        r"(showing|depicting|displaying|saying|holding|containing)\b",
    ),
    (6, _A.DESCRIPTION, r"\b(shown|depicted|displayed|painted|printed|written) (in|on)\b"),
    (
        4,
        _A.DESCRIPTION,
        r"\bwhich (one|\w+)(?<!side)(?<!way)(?<!direction) (?!.* or\b)(is it|is the (target|goal"
        r"|one)"
        r"|do you mean|are you looking for|should i find|am i looking)\b",
    ),
)
