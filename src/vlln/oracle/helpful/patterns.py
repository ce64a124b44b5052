"""The word patterns :mod:`.recognise` tries, over normalised words (lower case, contractions
spelled out, slips in cue words corrected).

Each pattern reads a class of phrasings, not single questions; the paper's questions ("Is
this the one?", "Am I close?", "What is next to it?", "Should I stop?") match none of them.
"""

from __future__ import annotations

import re

from vlln.oracle.classifier.entities import ROOM_SYNONYMS

_STOREY = r"(floors?|storeys?|story|stories|levels?)(?! lamp)"
_PLACE = r"(room|area|place|spot|part|section|space|wing|side|end|zone|" + "|".join(
    sorted(ROOM_SYNONYMS, key=len, reverse=True)
)
_PLACE += ")"
_ROOM = "(room|" + "|".join(sorted(ROOM_SYNONYMS, key=len, reverse=True)) + ")"
_HERE = rf"(here|in here|this {_PLACE}|this (\w+ )?{_PLACE})"
_SELF = r"(i|we)"
_WALKED_PAST = (
    r"(been|came|gone|went|walked|passed|visited|checked|searched|explored|looked|covered|seen)"
)
_WALKED = (
    r"(been|be|come|came|gone|go|went|walked|walk|passed|pass|visited|visit|checked|check|"
    r"searched|search|explored|explore|looked|look|covered|cover|seen|see|entered|enter)"
)

FLOOR = re.compile(
    r"\b(upstairs|downstairs|up stairs|down stairs|(go|walk|climb|head) (up|down) the stairs|"
    r"(take|use|climb) the stairs|(how many|number of) " + _STOREY + r"|floor level|"
    r"(wrong|right|correct|same|this|my|other|another|different|which|what|upper|lower|top|"
    r"ground|bottom|first|second|third|next|main|entrance|basement) "
    + _STOREY
    + r"|(up|down) (a|one) "
    + _STOREY
    + r"|floor (above|below)|(one|two|three|single|multi) ?(storey|story|level|floor)s?|"
    r"(floor|level|storey) (i am|i was|i started|we are|with the|as the|of the)|"
    r"(share|shares|sharing) (a|the) (floor|level|storey)|(entrance|entry|ground|street) level|"
    r"level with the|(change|changing|switch|switching) " + _STOREY + r"|"
    r"^(go |is it |it is )?(up|down) or (up|down)|(go|head|it|i|we|target) (up|down) or (up|"
    r"down)|(up|down) or (up|down) (from|of) (me|here|us)|(above|below) or (above|below)( me| us"
    r"| here)?|"
    r"(go|head|climb|move|going|heading|climbing) (up|down)( there| then| now| here)?$|"
    r"climb (up|down))\b"
)
# "should I take these stairs?", "are the stairs the way?": stairs to be walked, not a
# landmark ("is it near the stairs?", "do I go left after the stairs?").
STAIRS = re.compile(
    r"\b(take|taking|use|using|need|climb|climbing|(go|going|head|heading) (up|down)|up|down) "
    r"(the |these |those |this |that |a |any |some )?(\w+ )?(stairs|staircase|stairway|"
    r"stairwell)\b|\b(stairs|staircase) (up|down|the way)\b"
)
# "is it in the basement?" asks where the target is; "am I in the basement?" is the paper's.
STOREY_ROOM = re.compile(
    r"\b(in|on|to|into|from) (the |a |an )?(basement|cellar|attic)\b|\b(is there|have|has|"
    r"contains?) (a |an )?(basement|cellar|attic)\b|^(basement|cellar|attic)\b"
)
ASKER_IN = re.compile(r"\b(am i|are we|i am|we are|is this|this is)\b")
# "how many floors?", "more than one floor?": storeys, not objects.
STOREY_COUNT = re.compile(
    rf"\b(how many|number of|more than (one|two|three|\d+)|(just|only) one) {_STOREY}"
)
COUNT = re.compile(
    r"\b(how many|number of|(just|only) one|(is|are) there (any )?(other|several|many|multiple|"
    r"two|three|another|only one|more(?! than))|more than one|only one)( (other|more|such|of))? ?"
    r"(?P<thing>\w*)"
)
# "how many drawers does the dresser have?" counts parts of one object, not objects; a room
# or the house "has" objects.
OWN_PARTS = re.compile(
    rf"\b(does|do|has|have) (the|this|that|a|an|it|its) (?!house|home|building|flat|{_PLACE})\w+"
)
MORE_COUNT = re.compile(
    r"\b(total (number|count)|counts? (the|all|them|up|of)|(a|the|me a|me the) (count|tally)|"
    r"is (this|that|it) the only|(the )?only (one|\w+) "
    r"in (the|this|that) (house|room|place|home)|a second (one|\w+)|more than (one|two|three|"
    r"four|five|six|\d+)|(a lot of|lots of|several|many) \w+ (in the house|or (just )?a few)|"
    r"(is|are) there (more|other|any other|a lot|lots)|any other \w+ (in|like|besides))\b"
)
# "is the shelf the only one of its kind here?": the only one, said of a thing.
ONLY_ONE = re.compile(r"\bthe only (?P<thing>\w+)\b")
IN_VIEW = re.compile(
    r"\b(in (my |your )?(view|sight)|(can|do|could) (i|we) (see|spot|make out|notice)|"
    r"i (can )?(see|spot)|from (here|where i am|this (spot|position|point|doorway|angle))|"
    r"within (my )?sight|visible|in front of me|can be seen|(am i|i am) looking at)\b"
)
# A count over the walk: "how many sofas did I see on the way?", "in rooms I have visited".
WALKED_COUNT = re.compile(
    rf"\b(on the way|so far|along the way|{_SELF} (have |had )?(already |not |never )?"
    r"(passed|seen|saw|visited|walked|been|checked|gone|went|come|came)|(did|have) "
    rf"{_SELF} (see|pass|seen|passed|visit|visited|walk|walked))\b"
)
IN_ROOM = re.compile(
    rf"\b(in here|this {_ROOM}|room (i am|we are) in|(?<!from )(?<!way )(?<!to )(?<!get )"
    r"(?<!got )(?<!came )here( right now)?$)\b"
)
WINDOW = re.compile(r"\bwindows?\b")
NEAR_WORDS = re.compile(
    r"\b(near|by|next to|beside|under|underneath|beneath|below|close|adjacent|facing|against|"
    r"in front of|behind|above|across from|opposite)\b"
)
PASSED = re.compile(
    r"\b(have|did) (i|we) (already |just )?((seen|see|spotted|spot|noticed|notice|looked at|look "
    r"at) (it|them|the)|(walk|walked) into it)\b|"
    r"\b((did|have|had|has) (i|we) (already |just )?(pass|passed|miss|missed|overshoot|"
    r"overshot|(go|gone|went|walk|walked) (right |straight |just )?(past|by))|(i|we) "
    r"(think (i|we) )?(already |just )?(passed|missed|overshot|(went|walked) (right |just )?"
    r"(past|by))) (it|the|them)\b|\b(was|were) (it|they|the \w+( \w+)?) (visible|in (my )?"
    r"(view|sight))( \w+)* (earlier|before|at some point|back there|at one point)\b|"
    r"\b(could|might|may) (i|we) have (already )?(passed|missed|overshot|(walked|gone) (right "
    r"|just )?(past|by)) (it|the|them)\b|\b(was|were) (i|we) "
    r"(in|at) the (right|correct) (place|spot|room) (earlier|before|already)\b"
)
# "on track", "wrong turn", "was I closer a minute ago": the trend over the path; each match
# says whether the question proposes progress or its opposite (``worse``).
CLOSER = re.compile(
    r"\b((am i|are we|i am|we are|is the agent)( \w+)? (getting|going|moving|heading|walking|"
    r"coming) (any )?(closer|nearer|farther|further|warmer|colder|hotter)|am i( \w+)? (closer|"
    r"nearer|farther|further|warmer|colder|hotter)|(did|have) i (get|got|gotten) (any )?(closer|"
    r"nearer|farther|further)|(closer|nearer) (now|than (before|earlier|when|at))|"
    r"(closer|nearer) or (farther|further)|(getting )?warmer or colder|hot or cold|"
    r"(is it|getting) (warmer|colder|hotter)|on (the )?(right |correct )?track|off (track|course)|"
    r"(?<!facing the )(?<!facing )(?<!point me in the )(right|correct|wrong) (way|direction|"
    r"path)(?! to (the|get|go|reach)\b)|(a|the) (right|wrong|correct) turn|wrong turn|(making|"
    r"made|make) (any |some |good )?progress|(was|were) (i|we) (closer|nearer)|(moving|going|"
    r"walking|heading|getting|wandering) (further |farther )?away)\b"
)
WORSE = re.compile(
    r"\b(farther|further|colder|wrong|off (track|course)|away|(was|were) (i|we) (closer|"
    r"nearer))\b"
)
REROUTE = re.compile(
    r"\b((i|we) (am|are|think i am|got|have got|feel|seem to be)( a bit| so| totally| "
    r"completely| really| kind of| kinda)? (lost|stuck|confused|disoriented)|am i lost|"
    r"lost (track|my way|my bearings)|no idea where (i am|to go)|do not know where (i am|to go)|"
    r"help (me |us )?(get|getting|find|finding|reach|navigate)|got lost)\b|"
    r"\b(can|could|would) you help( me| us)?( please)?$|^(please )?help( me)?( please)?$|"
    r"^(so |totally |completely )?lost\b|\bback on track\b|\bwhere am i relative to\b"
)
# --- the walked path: rooms and places visited (:class:`.recognise.PathTopic`) --------------
AREA = re.compile(
    r"\b(right|wrong|correct) (part|wing|area|section|side|end|zone) of the "
    r"(house|home|building|flat|place|apartment)\b|\bin the (right|wrong|correct) "
    r"(area|wing|part|section|zone)\b"
)
START = re.compile(
    rf"\b(same|the) {_PLACE} {_SELF} (started|start|began|begin|was at first)\b|"
    rf"\b(back )?(where|to where) {_SELF} (started|began|came in)\b|"
    r"\b(starting|start) (point|room|position|place)\b"
)
RETRACING = re.compile(
    r"\b(retracing|retraced|doubling back|doubled back|backtracking|backtracked|"
    r"(in|around in|round in|round and round in) (a )?(circles?|loops?)|(going|walking|moving|"
    r"wandering|been) back and forth|"
    r"same (rooms?|places?|spots?|ground|way) (again|over|twice)|walked (in )?a loop|"
    r"going round|(the )?same (path|route) (again|twice))\b"
)
TARGET_ROOM = re.compile(
    rf"\b(rooms?|areas?|parts?|places?) (of the house )?(that |which |where )?{_SELF} "
    rf"(have |had )?(already |just )?(not )?{_WALKED_PAST}\b|"
    rf"\b(skip|skipped|miss|missed|overlook|overlooked) (a|any|the|some) {_PLACE}\b|"
    rf"\b{_SELF} (have |had )?(already |not |yet )*{_WALKED_PAST} (in |into |through |to )?"
    r"(the|its) "
    rf"({_PLACE} )?(of the (house|home|flat) )?(with|where|it is in|that has)\b|"
    rf"\b(have|did) {_SELF} (already )?{_WALKED} "
    rf"(in |into |through )?(its|the target s|the goal s) {_PLACE}\b"
)
ROOMS = re.compile(
    rf"\b(which|what|how many|number of) (rooms|places|areas|parts)( \w+)? (have|did|had) "
    rf"(not )?{_SELF}\b|\b(have|did) (i|we) (explore|explored|search|searched|check|checked|"
    r"cover|covered|look through|looked through) (enough|all|every|most|much|the whole|"
    r"everything)\b|"
    rf"\b(rooms|places|areas) {_SELF} (have|had)( already| yet)? (not|never)\b|"
    rf"\b(not yet|never|have not|had not) {_WALKED} (in|into|through)? ?(which|what|any)\b|"
    rf"\bwhere (have|did) {_SELF} (already )?{_WALKED}\b"
)
HERE = re.compile(
    rf"\b(have|had|did) {_SELF} (already |ever |previously |just |not |yet )*{_WALKED} "
    rf"(in |into |inside |through |to |at |past |around )?{_HERE}\b|"
    rf"\bbeen {_HERE}( already| before)?\b|\b{_SELF} have (already )?been {_HERE}\b|"
    r"\bfirst time (i am|i have|we are|we have|in|here|seeing|i see)\b|\b(have|had|did) "
    rf"{_SELF} (already |ever |just )?(been|gone|come|walked|visited|checked|searched|"
    rf"explored|passed|looked|visit|check|search|explore|look|go|walk) (in |into |through |to )?"
    rf"(the|a|any) {_PLACE}\b|\b(was|were) {_SELF} (in |at )?{_HERE} (before|earlier|already)\b"
)
# "is this the first time ...?", "have I never been here?": yes means not visited.
FIRST_TIME = re.compile(r"\b(first time|never|not been|not yet|new to me|not visited)\b")
# --- confirmation and the end of the search ----------------------------------------------
CONFIRMATION = re.compile(
    r"^((are|do) )?(you|you are) (really |very |absolutely )?(sure|certain|positive|confident)"
    r"( about (it|that|this)| of (it|that|this)| (that|this|it)( one)? (is|is not|isnt)( it| the"
    r" one| right| correct| the right one)?)?$|^how (sure|"
    r"certain) are you$|^(really|sure|certain)$|\bis (that|this|it) (really|definitely|"
    r"certainly) (it|the one)\b|\b(are you|you are) (really |very |absolutely |completely )?(sure|"
    r"certain|positive|confident)\b|\bhow (sure|certain|confident)\b|\bdouble ?check\b|"
    r"\b(can|could) you confirm\b|\bfinal answer\b|\b(be|are you) (mistaken|wrong)\b|"
    r"\bconfusing (it|them)\b|\bjust guessing\b|\b(can|could) you tell from (here|this)\b|"
    r"\b(is|it is) (that|this|it) definitely\b|\b(is it possible|could it be) (it is |its )?(the "
    r"other|another|a different)\b|^(so |and |but )?(absolutely |totally |completely |really |100 "
    r"percent )?(positive|sure sure|certain|definitely|for sure|sure|you sure|no doubt)( about "
    r"(it|that))?$|"
    r"^(you|and you|so you|but you|you are) (really |very |absolutely )?(sure|certain|positive)\b|"
    r"\b(no|any|without( a)?|beyond( any)?) doubts?\b|\b(really|actually|definitely|truly|"
    r"honestly) mean (this|that|it|the)\b|\b(chance|possibility|possible|maybe)( that)? (it is|"
    r"its|this is|that is|it could be|it might be|you mean|you meant) (not )?(the other|another|"
    r"a different|the wrong)\b|\b(safe|fair|right|correct) to say\b|\b(should|shall|can|do|"
    r"must) (i|we) ((commit|settle) (to|on|for)|(go|stick) with|lock in) (this|that|it|the)\b"
)
# "are you sure?", "positive?": certainty alone, which "yes, I am sure" answers.
CERTAINTY_ALONE = re.compile(
    r"^(so |and |but |ok )?((are|do) )?(you|you are) (really |very |absolutely |totally |100 "
    r"percent )?(sure|certain|positive|confident)( about (it|that|this)| of (it|that|this))?$|"
    r"^(absolutely |totally |completely |really |100 percent )?(really|positive|sure( sure)?|"
    r"certain|definitely|for sure|no doubt( about (it|that))?|how (sure|certain) are you)$"
)
DONE = re.compile(
    r"^(so |and |ok |okay )?(i am|we are|am i|are we) (all )?(done|finished)\b|\b(am i|are we) "
    r"(all )?(done|finished)\b|\b(end|finish|conclude|wrap up|complete|call off) "
    r"(the |my |this )?(search|episode|task|hunt|mission|looking|searching|here|now)\b|"
    r"\bstop (the |my |this )?(search|searching|looking|episode|task|hunt)\b|"
    r"\b(ok|okay|fine|safe|alright|all right|time|good) to (finish|end|quit|wrap up|call it)"
    r"\b|\bcall it (done|a day|quits|finished)\b|\b(keep|continue|carry on) (searching|looking|"
    r"exploring)\b.* or\b|\bor (is this it|is that it|have i (got|found) it|am i (done|there))\b|"
    r"\b(need|have) to (keep|continue|carry on) (searching|looking|going|exploring)\b|"
    r"\bno need to (look|search|keep|go|continue)\b|\b(need|have) to (look|search) (any )?"
    r"(further|more|on|elsewhere)\b|\b(going to|gonna|will|about to) (stop|end|finish)\b.*\b(ok|"
    r"okay|fine|alright|right)\b|\bsearch (is )?over\b|\bend of (the|my|this) (search|episode|"
    r"task|hunt)\b"
)
# --- the candidates in view ----------------------------------------------------------------
THE_ONES = (
    r"(\b(the|this|that|which) (\w+ )?ones?\b|\bof (them|these|those|the two)\b|\bones? or\b)"
)
WHICH = re.compile(
    r"\bwhich (one( of (them|these|those|the two))?|of (them|these|those|the two))( \w+)? "
    r"(is (it|the target|the goal|the one|yours|mine|the right one|the correct one)|(do|did) "
    r"you mean)\b|^which (one|of them)( is it)?$"
)
# "which one?", "between the white chair and the black chair", "the one by the door or ...",
# "left or right?" (not "should I turn left or right?"), "help me choose between these".
CHOICE = re.compile(
    r"\bwhich (one|ones|of (them|these|those|the))\b|^which$|\bwhich is (the one|it|yours)\b|"
    r"\bbetween the \w+( \w+)? and the\b|\bbetween the .* and the ones?\b|"
    r"\bthe (one|\w+ one) .*\bor (the|by|in|on|with)\b|\b(\w+) (one )?or (the )?(\w+ ){1,2}one\b|"
    r"\b(front|back|first|second|top|bottom) one or\b|\bor (the )?ones?\b|"
    r"\bor (to |on )?the (left|right)\b|\bthe (\w+ )?(?P<noun>\w+) or the (\w+ )?(?P=noun)\b|"
    r"\b(choose|pick|decide|tell|select) between\b|\bbetween (these|those) (two|2|three|3|\w+s)\b|"
    r"\b(it|be|mean) the (?!(one|door|doorway|corridor|hallway|hall|way|path|stairs|staircase|exit|"
    r"turn|room|opening|passage)\b)\w+ (on|to|at) (the|my|your) (left|right|middle)( hand)?"
    r"( side)?$"
)
# "left or right?" picks a candidate only where the message speaks of several ("two toilets
# in front of me - left or right?") or names one ("the sofa by my left hand or my right?");
# alone it is the paper's route question.
SIDE_CHOICE = re.compile(
    r"(?<!front )(?<!back )\b(left|right)\b(\W+\w+){0,5}? or\b(\W+\w+){0,5}? (?<!front )"
    r"(?<!back )(left|right)\b"
)
SEVERAL = re.compile(
    r"^the (?!.*\b(is|are)\b)|\b(two|2|three|3|both|couple|several|candidates|multiple|these|"
    r"those|of them|ones|"
    r"which (?!(way|side|direction|track|one is it)\b)\w+)\b"
)
MOVES = re.compile(r"\b(turn|turning|go|going|head|heading|move|moving|walk|walking|veer)\b")
WHICH_DIMENSION = re.compile(r"\bwhich (?P<what>size|colou?r|side)\b")
RIGHT_SIDE = re.compile(r"\b((on|to|at) (the|your|my) right|right( hand)? side|right hand)\b")
# --- the target's surroundings ---------------------------------------------------------------
NEIGHBOURHOOD = re.compile(
    r"\b(what (else )?(is|are)( there)? around (it|the (target|goal|\w+))|(which|what) (things|"
    r"objects|furniture|items) (is|are) (around|near|next to|by|beside|close to)|what else "
    r"(is|are) (near|next to|by|beside|close to) it|(its|the) (surroundings|neighbou?rhood|"
    r"immediate vicinity)|(surrounds|surrounding) (it|the)|anything (around|near|by) (it|the))\b|"
    r"\bwhat (is|are)( there)? (directly |right |just )?(on top of|across from|opposite|on "
    r"(either|each|both) sides? of|behind|above|below|underneath|beneath|in front of|over) "
    r"(it|the)\b|\b(anything|something|stuff) (on top of|on|above|over|under|underneath|"
    r"beneath|below|behind|in front of) (it|the)\b|\bwhat (is|are) (it|the \w+( \w+)?) "
    r"(sitting|standing|resting|lying|placed|mounted|hanging|hung|sat|propped) (on|against)\b|"
    r"\bwhat (is|are) (the \w+( \w+)?) (near|close to|by)$|\bwhat (is|are)( there| \w+)? on "
    r"the (wall|walls) (near|by|next to|above|behind|beside|around|over) (it|the)\b|\bwhat (is|"
    r"are) (sitting|standing|resting|lying|placed|stacked|kept) (on|on top of|under|above|behind|"
    r"in front of) (it|the)\b"
)
# The relation a neighbourhood question asks about, by the words that ask it.
RELATIONS = (
    ("wall", re.compile(r"\bon the walls?\b")),
    ("support", re.compile(r"\b(sitting|standing|resting|lying|placed|sat|propped) on$|\bon$")),
    ("above", re.compile(r"\b(on top of|above|over|on) (it|the)\b")),
    ("under", re.compile(r"\b(under|underneath|beneath|below) (it|the)\b")),
    ("behind", re.compile(r"\bbehind\b")),
    ("front", re.compile(r"\bin front of\b")),
)
# --- questions about nothing in the house ------------------------------------------------------
# Words that tie a question to the search: the target, places, moves, seeing, helping.
_ON_TOPIC = (
    "it its this that these those them they one ones here there target goal object thing "
    "things item items stuff house home room rooms place way left right straight ahead back "
    "forward front behind near far close closer next side floor wall door window stairs "
    "go going get getting turn move walk head find found look looking see seen view visible "
    "search searching stop done where colour color size big small describe "
    "help hint clue tip tips lost again repeat answer question mean meant sure correct wrong "
    "previous last first step steps meter meters metre metres distance direction route path "
    "yes no ok okay thanks thank hello hi hey sorry"
)
ON_TOPIC_WORDS = frozenset(_ON_TOPIC.split())
# "how do I bake bread?": a doing that is no move, look or question of the search.
_MOVES_AND_LOOKS = (
    r"(get|go|reach|find|locate|spot|see|know|tell|recognise|recognize|identify|distinguish|pick|"
    r"choose|select|turn|walk|move|head|navigate|approach|enter|exit|leave|open|cross|pass|climb|"
    r"stop|finish|end|complete|search|look|explore|proceed|continue|return|come|follow|use|ask|"
    r"describe|say|do|avoid|check|confirm|verify|start|begin|take|be|have|notice|miss|"
    r"arrive|travel|figure|work|spot|fit|squeeze|orient|face|rotate|back|step)"
)
HOW_TO = re.compile(
    rf"\bhow (do|can|could|should|would|shall) (i|we|you|one) (?!{_MOVES_AND_LOOKS}\b)\w+|"
    rf"^how to (?!{_MOVES_AND_LOOKS}\b)\w+"
)
# --- wider phrasings: a verdict on the walk, named alternatives, what is on or near it ------
# "was going into the laundry a mistake?", "did I detour a lot?", "how much closer than at
# the start?": a verdict on the walked path, answered from its start and its last metres.
ROUTE = re.compile(
    r"\b(was|were|is) (that|it|this|\w+ing)( \w+){0,4} (a |the )?(mistake|wrong (call|choice|"
    r"move|decision|idea)|bad (call|choice|move|idea|decision)|waste of time)\b|\bwas (that|it|"
    r"this) (necessary|needed|worth it)\b|\b(did|have) (i|we) (mess|messed|screw|screwed) up\b|"
    r"\b(i|we) (think (i|we) )?(messed|screwed) up\b|\b(i|we)( \w+){0,4} detour\w*\b|"
    r"\b(am|are|was|were|have|did) (i|we)( \w+){0,2} (going|gone|taken|taking|took|went|come|"
    r"came) the long way\b|"
    r"\b(shortest|best|quickest|fastest) (way|route|path) (so far|from (the start|where))\b|"
    r"\b(route|path) (i|we) (have |had )?(taken|took|walked|came|followed)\b|"
    r"\bturn(ed)? (around|back) too (early|soon|late)\b|\bcompared (to|with) (before|earlier|"
    r"the start|when)\b|\bthan (at|when (i|we)) (the )?(start|started|began|first)\b|"
    r"\bsince (the start|(i|we) (started|began|set off))\b|\b(am i|are we) (moving|going|heading|"
    r"walking|getting) (toward|towards|closer to) (it|the \w+( \w+)?)( \w+)? or (away|farther|"
    r"further)\b"
)
# "did I turn around too early?", "did I detour?": yes says the walk went wrong.
ROUTE_WORSE = re.compile(
    r"\b(mistake|wrong|bad|waste|mess|messed|screw|screwed|detour\w*|long way|too (early|soon|"
    r"late))\b"
)
BACKTRACK = re.compile(r"\b(should|shall|do|must) (i|we)( \w+)? (backtrack|double back)\b")
WITHIN_REACH = re.compile(
    r"\b(have|did|had) (i|we) (already |ever |just )?(been|come|get|got|gotten|walked) (within|"
    r"close to|near) (a few|a couple of|\w+) (meters|metres|steps|feet) of\b"
)
ENDING_UP = re.compile(
    r"\b(keep|kept|keeps) (ending up|coming back|getting back|returning|going back|landing)"
    r" (in|to|into) (the )?same\b|\bbeen this way (already|before)\b"
)
MISSED_ROOM = re.compile(
    r"\b(skip|skipped|miss|missed|overlook|overlooked) (a|any|the|some|its|the \w+ "
    rf"s) (\w+ )?{_PLACE}s?\b|\bwhich {_PLACE} (did|have) (i|we) (miss|missed|skip|skipped)\b|"
    r"\b(did|have) (i|we) (overlook|overlooked|miss|missed) (it|the \w+( \w+)?) in the\b|"
    r"\b(somewhere|in a \w+|in a room|in a place|in one of the rooms) (i|we) (have |had )?"
    r"(already )?(looked|missed|been|checked|searched|passed|skipped|seen)\b|\b(was|were) (one"
    r"|any) of (those|them|these)( rooms| \w+s)? (the (right|correct) (one|room)|it)\b"
)
WRONG_AREA = re.compile(
    r"\bin (completely |totally |entirely |quite |really )?the (wrong|right|correct) (area|wing|"
    r"part|section|zone)\b"
)
# "is it up here or do I need to head back down?", "stairs or no stairs?".
FLOOR_MORE = re.compile(
    r"\b(up|down) (here|there) or\b|\bor (do |should |must )?(i|we)?( need to| have to)? ?(go|"
    r"head|climb|walk) back (up|down)\b|\b(go|head|climb|walk) (back )?(up|down)( the \w+)? "
    r"to (find|look|search|check|get to)\b|\b(stairs|staircase) or (not|no)\b|\b(up|down) "
    r"(in|to|into) the (loft|attic|basement|cellar)\b|\b(in|into) the loft\b"
)
# "am I correct that ...", "did I get it wrong?", "is my search complete?".
CONFIRM_CLAIM = re.compile(
    r"\b(am i|are we) (correct|right) (that|in thinking|to think) (?!(i|we) (am|are)\b)|"
    r"\b(did|have) (i|we) (get|got|gotten) (it|this|that) wrong\b|\bor (did|have) (i|we) "
    r"(get|got|gotten|pick|picked) (it |the )?wrong\b"
)
DONE_MORE = re.compile(
    r"\b(search|task|hunt|job|mission) (is |now )?(complete|completed|over|finished|done)\b|"
    r"\b(have|did) (i|we) (succeed|succeeded|accomplished|completed|made it)\b|\bstop or "
    r"(is|are) there\b|\b(better|closer|other) match\b"
)
# "how many plants are in my field of view?", "one of many shelves?", "total sofas?".
FIELD_OF_VIEW = re.compile(r"\bfield of (view|vision)\b")
COUNT_MORE = re.compile(
    r"\bone of (many|several|a few|lots|a lot|multiple|the many|a couple)\b|\bonly a (couple|"
    r"few)\b(?! (of )?(meters|metres|steps|feet|more|minutes))|^(so |and |the )?total \w+|"
    r"\btotal \w+ in (the|this) (house|home|place|building)\b"
)
# What is on it, near it or which thing it rests on, asked other ways.
AROUND_MORE = re.compile(
    r"\bwhat (\w+ )?(is|are) (sitting|standing|resting|lying|placed|stacked|kept) (on|on top of|"
    r"under|above|behind) (it|the)\b|^what (is|are) on (it|the (?!floor|wall|ceiling|left|"
    r"right)\w+( \w+)?)$|\b(is|are) there (a|an|any|some) \w+( \w+)? (on|on top of|under|above|"
    r"over) the \w+( \w+)?$(?<!question)(?<!questions)|\bon (either|each|both) sides? of "
    r"(it|the)\b|\b(anything|something) "
    r"(\w+ )?(next to|near|by|around|beside|close to) (it|the)\b|\blandmarks? (near|next to|by|"
    r"around|close to|at|for) (it|the)\b|\b(use|used|serve) as (a )?landmarks?\b|\b(which|what|"
    r"nearest|any) (\w+ )?landmarks?\b|\b(close|near|next) to "
    r"(that|the|this|a) (door|doorway|entrance|opening)\b"
)
# "is the cushion on a chair, a bed or a sofa?": what it rests on, when both name things
# (:func:`.recognise._around`); "near the shower or the sink?": what it stands by.
SUPPORT_CHOICE = re.compile(
    r"\b(on|sitting on|lying on|resting on|standing on|hanging on) (?P<one>(a|an|the) \w+( \w+)?"
    r"(,? (a |an |the )?\w+( \w+)?)?),? or (?P<other>(on )?(a |an |the )?\w+( \w+)?)"
)
NEAR_CHOICE = re.compile(
    r"^(?!(am|are|must|should|do|can) (i|we)\b).*\b(near|next to|by|beside|close to|closer to) "
    r"(?P<one>(the|a) \w+( \w+)?) or (?P<other>(near |by |next to )?(the |a )?\w+( \w+)?)"
)
# A question about something else than the house: maths, weather, money, food, animals,
# trivia, jokes. Only where it names nothing of the house (:func:`.recognise._off_topic`).
ELSEWHERE = re.compile(
    r"\b(square root|plus|minus|divided by|multiplied|math|maths|equation|weather|rain|raining|"
    r"snow|snowing|sunny|forecast|stocks?|shares|invest|investing|crypto|bitcoin|money|salary|"
    r"calories|recipe|protein|vitamins?|diet|octopus\w*|dolphins?|dinosaurs?|animals?|joke|"
    r"jokes|riddle|poem|fun fact|interesting (fact|thing)|something interesting|capital of|"
    r"president|election|football|soccer|movie|movies|song|songs|meaning of life|your name|"
    r"how old are you|favou?rite)\b"
)
# Words that tie a question to the house, against :data:`ELSEWHERE`: rooms and the search.
_HOUSE = (
    "target goal object item house home room floor wall door window stairs left right "
    "straight ahead forward behind near far closer turn walk move head find found search "
    "searching view visible step meter metre distance direction route path colour color "
    "lost stop done"
)
HOUSE_WORDS = frozenset(_HOUSE.split()) | {w for room in ROOM_SYNONYMS for w in room.split()}
