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
    # The navigator's room stated for confirmation, as the last sentence: "i am in a bedroom?"
    (
        7,
        _X.AGENT_ROOM,
        r"^(i am|we are) ((now|currently|still|already|standing|right|finally) )*in (the|a|an"
        rf"|this|my|our) (\w+ )?({ROOM_WORDS})( now| right| yes| correct| right now| no| or not"
        r"| then)?\Z",
    ),
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
        r"(?<!turn )(?<!rotate )\bhow (far|close|near|long|many (rooms|doors|turns|corridors|steps?"
        r"|meters?|feet|moves?|more)|much (further"
        r"|farther|longer|more|far))\b",
    ),
    (4, _X.DISTANCE, r"\b(distance|far away)\b|(?<!turn )(?<!rotate )\bhow far\b|^far$"),
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
        r"^(is|are) (it|they|this|that|the (\w+ )?\w+) ((still|very|quite|too|really|pretty|so"
        r"|that) )?(far|close|near|nearby|distant|far off)( or (far|close|near|not))?( (from|to)"
        r" (here|me|us|where i am|my position)| away| by)?$|\b(far|near|close) or (far|near"
        r"|close)\b|^(near|close|far|far away)( or not)?$",
    ),
    # A walk described: "is it a long way", "is the sink a short walk from here".
    (
        8,
        _X.DISTANCE,
        r"\b(a|the) (long|short|little|quick) (walk|way|trip|distance|journey|ride|hike)\b",
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
        r"|check|seen|passed|missed)",
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
    # A storey named for the navigator: "is this the ground floor".
    (
        8,
        _X.UNKNOWN,
        r"^(is|are) (this|that|here|it|we|i) (on )?(the )?(ground|upper|lower|top|first|second"
        r"|basement|main|bottom|right|same|correct) (floor|storey|level)$",
    ),
    # The oracle itself: what may be asked, what it knows, whether it hears.
    (
        8,
        _X.UNKNOWN,
        r"\b(can|may|could|should|am i allowed to) (i|we) ask\b|\b(kind|type|sort) of questions"
        r"\b|^where (are|were) you\b|\bwhere everything is\b|\b(know|knows|knowledge of) (this|the"
        r"|the whole|the entire)"
        r" (house|home|apartment|place|layout|map)( well| by heart| at all)?$|\b(can|do) you (hear"
        r"|understand) (me|us)\b|\b(have|got|use|see) (access to )?(a|the|any) (map|floor plan"
        r"|layout|blueprint)\b",
    ),
    (
        6,
        _X.UNKNOWN,
        r"^(are|were) you\b(?! (\w+ )?(looking|talking|describing|referring|meaning|thinking"
        r"|asking|searching))(?! sure (that|this|it|the|about)\b)",
    ),
    # Mishaps of the navigator: "i bumped into something, is that a problem?"
    (
        8,
        _X.UNKNOWN,
        r"\b(is|was) (that|this|it) (a problem|an issue|a mistake|bad|allowed|dangerous|ok|okay"
        r"|a bad thing|fine|normal)$|\b(bumped|crashed|collided|fell|tripped|hit the wall"
        r"|hit a wall|knocked"
        r" over)\b",
    ),
    # What the house has: "the house has how many floors", "does the flat have a garden".
    (
        9,
        _X.UNKNOWN,
        r"^(the|this|your|whole|entire) (house|home|apartment|flat|building) (has|have|got"
        r"|contains?)\b|\b(does|do|has) (the|this|your) (house|home|apartment|flat|building)"
        r"\b",
    ),
    (6, _X.UNKNOWN, r"\bfor me to use\b|\bcan i use\b"),
    # Doors and lights, the room the navigator stands in, what comes after finding the target.
    (
        5,
        _X.UNKNOWN,
        r"^(is|are) the (\w+ )?(door|doors|window|windows|light|lights|gate)( (to|of|into) the"
        r" \w+)? (open|closed|locked"
        r"|shut"
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
    (
        6,
        _X.UNKNOWN,
        r"\b(morning|evening|afternoon|night|daytime|today|tomorrow|yesterday|raining|sunny)\b",
    ),
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
    (
        6,
        _X.UNKNOWN,
        r"^(is|are)\b.*\b(in|inside) (the|this) (house|home|apartment|building)( at all| even)?$",
    ),
    # Chores for the house, not the search: "can i turn on the light", "help me find something".
    (
        8,
        _X.UNKNOWN,
        r"\b(turn|switch) (on|off) (the |a )?(light|lights|lamp|tv|television|radio|music)\b"
        r"|\bhelp (me|us) (find|with|look for) (something|anything|stuff)\b",
    ),
    # A room described, not the target placed in it: "is the kitchen big".
    (
        4,
        _X.UNKNOWN,
        rf"^(is|are) the ({ROOM_WORDS}) (big|small|large|huge|tiny|far|close|near|nearby"
        r"|upstairs|downstairs|open|empty|dark|bright|clean|messy|locked|occupied|free"
        r"|spacious|cold|warm|long|short|wide|narrow)$",
    ),
    (
        4,
        _X.UNKNOWN,
        r"\b(still|anywhere|somewhere) in (the|this) (house|home|apartment|building)\b",
    ),
)
