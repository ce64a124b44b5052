"""The cues for other questions: the navigator's own situation, the house, the oracle.

Which room the navigator is in, how far it still has to go, whether it is getting closer or
can see the target, what surrounds it, and everything off the task. Like
:mod:`vlln.oracle.question_cues`, they read normalised, rephrased text.
"""

from __future__ import annotations

from vlln.oracle.question_cues import ROOM_WORDS, OtherTopic, Rule

# What surrounds the agent, not the target: "the thing on my left", "what is behind me".
_AROUND_ME = (
    r"((on|to|at) (my|our) (left|right)|(left|right) of (me|us)|(in front of|behind|beside"
    r"|next to|near) (me|us))\b"
)
_X = OtherTopic

# Other: what privileged knowledge of the agent's state answers.
OTHER_RULES: tuple[Rule, ...] = (
    (
        7,
        _X.AGENT_ROOM,
        r"\b(which|what) (room|part of the house|area|place) (am i|are we|is this|is here"
        r"|this is)"
        r"|\b(which|what) (room|floor|area|place|part of the house)( \w+){0,2} (am i|are we)\b",
    ),
    (
        7,
        _X.AGENT_ROOM,
        r"\bwhere (\w+ )?am i\b|\bwhere (\w+ )?are we\b(?! (going|headed|heading))"
        r"|^(is this|is that|are we in|is here|is this room|is this place) (the |a )?"
        rf"({ROOM_WORDS})$",
    ),
    (6, _X.AGENT_ROOM, r"\b(am i|are we) ((standing|currently|now|still) )?in (the|a|an)\b"),
    (8, _X.AGENT_ROOM, r"\b(room|place) (i|we) (am|are) (\w+ ){0,2}in\b"),
    (
        8,
        _X.AGENT_ROOM,
        r"(?<!from )(?<!to )\b(my|our) (current |present )?(location|position|room|whereabouts"
        r"|pose|coordinates)\b",
    ),
    (
        7,
        _X.DISTANCE,
        r"\bhow (far|close|near|long|many (steps?|meters?|feet|moves?|more)|much (further"
        r"|farther|longer|more|far))\b",
    ),
    (4, _X.DISTANCE, r"\b(distance|far away|how far)\b|^far$"),
    (
        5,
        _X.DISTANCE,
        r"\b(number|count) of (\w+ )?(steps|actions|moves|turns|meters)\b|\bremaining\b",
    ),
    (
        7,
        _X.DISTANCE,
        r"^(is|are) (it|they|the (\w+ )?\w+) ((still|currently|now|very|really) )?(within \w+ "
        r"(meters?|steps?|feet|m)|close by|far from|near me|close to me)\b",
    ),
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
    (
        6,
        _X.PROGRESS,
        r"\b(have|did) (i|we) (already |not |not yet |yet )?(been|visit|visited|search|searched"
        r"|check)",
    ),
    (5, _X.VISIBILITY, r"\bcan (i|you) see (it|the|them|this)\b|\bdo you see\b"),
    (5, _X.VISIBILITY, r"\bwhat (can|do|could) (i|you|we) see\b"),
    # The navigator's floor, counts over the house, the navigator's own belongings.
    (
        6,
        _X.UNKNOWN,
        r"\b(this|same|current|my|our|which|what|another|other|different) floor\b"
        r"(?! (of|lamp|lamps|mat|rug|cushion|tiles?|boards?)\b)",
    ),
    (4, _X.UNKNOWN, r"^how many\b"),
    (4, _X.UNKNOWN, r"\bwhere (is |are )?(my|our) (?!(target|goal)\b)\w+"),
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
        r"^(is|how (big|large|small|old|many \w+) is) ((the|this|that|your) )?(whole |entire )?"
        r"(house|home|apartment|flat|building)\b|^(house|home|apartment) \w+$",
    ),
    (6, _X.UNKNOWN, r"^why\b|^((can|could|would|will) you )?help( me| us)?( out| please)*$"),
    # Favours the oracle cannot do, the navigator's own needs, introductions.
    (
        7,
        _X.UNKNOWN,
        r"^(can|could|would|will) you (please )?(turn (on|off)|switch|open|close|shut|bring"
        r"|fetch|carry|pick up|fly|cook|play|sing|dance|clean|hold|wait|repeat|speak)\b",
    ),
    (
        6,
        _X.UNKNOWN,
        r"\b(tired|bored|hungry|thirsty|sleepy|joke|weather|(a|some) (break|rest|nap|pause))\b"
        r"|\bi am (the|a|an|your) (\w+ )?(agent|robot|navigator|assistant|bot)\b|\backnowledge\b",
    ),
    (8, _X.UNKNOWN, r"\bhow (do|did|can|could|would) you (know|tell(?! me)|be sure|remember)\b"),
    (6, _X.UNKNOWN, r"^what (is|else is|objects are|things are) in (this|the current|my) room$"),
    (
        5,
        _X.VISIBILITY,
        r"\b(in view|in sight|in my view|on screen|in the (picture|image)|field of view)"
        r"|\bvisible\b(?! (?!(from|to|now|yet|here|there|at|in|on)\b)\w+)",
    ),
    (3, _X.UNKNOWN, r"\b(episode|mission|simulation|session|experiment|task)\b"),
    (
        8,
        _X.AGENT_ROOM,
        r"\b(what|which) (kind|type|sort) of (room|place|area) (is this|is here|am i|are we"
        r"|this is)\b",
    ),
    (
        5,
        _X.VISIBILITY,
        r"\b(view|image|camera|frame|picture) (contain|contains|show|shows|include|includes)\b",
    ),
    (6, _X.UNKNOWN, r"\bwhat can you (do|help)\b|^what do you mean\b"),
    (6, _X.UNKNOWN, r"\bfor me to use\b|\bcan i use\b"),
    # Doors and lights, the room the navigator stands in, what comes after finding the target.
    (
        5,
        _X.UNKNOWN,
        r"^(is|are) the (door|doors|window|windows|light|lights|gate) (open|closed|locked|shut"
        r"|unlocked|on|off)\b|\b(when|once|after|if) (i|we) find (it|the)\b",
    ),
    (5, _X.UNKNOWN, r"^(is|are) (this|that) (room|place|area|hallway|corridor|house|space)\b"),
    (8, _X.UNKNOWN, r"^(is|are) (this|that) (a|an) \w+ or (a|an) \w+\b"),
    (
        9,
        _X.UNKNOWN,
        r"^how (big|large|small|wide|long) is (this|my|our|the current) (room|place|area|corridor"
        r"|hallway)\b",
    ),
    (4, _X.PROGRESS, r"\b(soon|eventually)\b"),
    (6, _X.UNKNOWN, r"\bwhat (time|day|date)\b|\b(biggest|largest|smallest|bigger|main) room\b"),
    (
        5,
        _X.UNKNOWN,
        r"^is it (so |very |too )?(dark|bright|cold|hot|warm|quiet|noisy|safe|dangerous)"
        r"( (in|here|outside|now)\b|$)",
    ),
    (
        9,
        _X.UNKNOWN,
        r"^(is|are) (this|that|it|the) (\w+ ){0,2}(house|home|apartment|flat|building)$"
        r"|^what (is|are) (the|this|your) (house|home|apartment|place|building) like$",
    ),
    (4, _X.UNKNOWN, r"^(is|are)\b.*\b(in|inside) (the|this) (house|home|apartment|building)$"),
    # A room described, not the target placed in it: "is the kitchen big".
    (
        4,
        _X.UNKNOWN,
        rf"^(is|are) the ({ROOM_WORDS}) (big|small|large|huge|tiny|far|close|near|nearby"
        r"|upstairs|downstairs|open|empty|dark|bright|clean|messy|locked|occupied|free"
        r"|spacious|cold|warm)$",
    ),
    (
        4,
        _X.UNKNOWN,
        r"\b(still|anywhere|somewhere) in (the|this) (house|home|apartment|building)\b",
    ),
)
