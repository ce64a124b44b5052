"""The cues for route questions: the target's direction, the way there, the next move.

Orientation cues ask where the target lies relative to the navigator, path cues ask for a way
through the house, step cues for one immediate action. Like
:mod:`vlln.oracle.question_cues`, they read normalised, rephrased text.
"""

from __future__ import annotations

from vlln.oracle.question_cues import ROOM_WORDS, WAY_PARTS, RouteKind, Rule

_O, _P, _S = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP
_NOT_WH = r"^(?!(what|which|where|how|why)\b)"
# "before i go on" sets the scene for another question; it proposes no move.
_NOT_AFTER = r"(?<!before )(?<!after )(?<!when )(?<!once )(?<!if )(?<!until )(?<!while )"
# "the right side table" names a thing, not a side.
_SIDE_THINGS = r"(side )?(table|tables|board|boards|door|doors|drawer|lamp|cabinet)\b"

ROUTE_RULES: tuple[Rule, ...] = (
    # Route, orientation: the direction of the target.
    (4, _O, r"\b(which|what) direction\b"),
    (2, _O, r"\bdirection\b"),
    (
        3,
        _O,
        r"\bwhich (hand )?(way|side)\b|\bwhich hand\b|\bwhat side\b|\bpoint (me|at|to)\b"
        r"|\b(should i|do i|must i) (be )?(face|facing)\b|\b(north|south|east|west)\b",
    ),
    (
        3,
        _O,
        r"\b(on|to|at) (my|the|your) (left|right)( side| hand)?+(?! of (it|the|them)\b)"
        rf"(?! {_SIDE_THINGS})(?! (path|track|way|direction|route|road|room|floor|place)\b)",
    ),
    (4, _O, r"\b(left|right) (side |hand )?of me\b|\b(left|right) side or\b"),
    (
        3,
        _O,
        r"^(?!.*\b(left|right) side of (it|the|a|an|them)\b).*(?<!its )(?<!their )"
        rf"\b(left|right) side\b(?! of (it|the|them)\b)(?! {_SIDE_THINGS})",
    ),
    (2, _O, r"\bmy (left|right)\b"),
    (4, _O, r"\b(to|at|on) my (front|back)\b"),
    (
        3,
        _O,
        r"\b(more|further|slightly|bit|little) ((to|toward) )?((the|my) )?(left|right)\b",
    ),
    (6, _O, rf"\b(left|right) ({WAY_PARTS} )?or the (left|right) one\b"),
    (
        3,
        _O,
        r"^(is|are) (it|they|the (\w+ )?\w+) ((straight|right|directly|somewhere) )?(in front of"
        r"|behind|ahead of|to the (left|right) of|on the (left|right) of) (me|us)"
        r"( right now| now| currently)?$",
    ),
    # The same, stated for confirmation: "the bed stays in front of me?"
    (
        4,
        _O,
        r"^(it|they|the (\w+ )?\w+) (is|are|stays|stay|lies|lie|sits|sit|stands|stand|remains"
        r"|remain) ((straight|right|directly|somewhere|still) )?(in front of|behind|behind of"
        r"|ahead of|to the (left|right) of|on the (left|right) of) (me|us)( right now| now"
        r"| currently| yes| right)?$",
    ),
    (
        6,
        _O,
        r"\bhow (much|far|many degrees?) (\w+ ){0,4}(turn|rotate)\b|\b(turn|rotate) how (much|far"
        r"|many)\b",
    ),
    (
        3,
        _O,
        r"\b(behind|ahead) of (me|us)\b|\bbehind me\b|\b(in front|ahead) of me or\b"
        r"|\bwhere to (turn|look|face)\b"
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
    (5, _O, r"\b(relative|compared|with respect|in respect|in relation) to (me|where i am|my)\b"),
    (4, _O, r"\b(in front|ahead) (of me )?or behind\b|\bbehind (me )?or (in front|ahead)\b"),
    (5, _O, r"^(to|toward|towards) (where|which way)\b"),
    (
        5,
        _O,
        r"\bwhere (is|are) (it|they|the (\w+ )?\w+) ((on|to|at) (the |my )?)?(left|right|ahead"
        r"|behind|in front)\b",
    ),
    (3, _O, r"\b(to|for) see (it|them|the)\b"),
    (4, _O, r"\bin relation( to (me|us|where i am|my \w+))?$"),
    (3, _O, r"\bin the direction (i am|of)\b|\bwhere (lies|lie)\b|\bin which direction\b"),
    (
        5,
        _O,
        r"\bwhere is (it|the (\w+ )?\w+) (from here|from me|from my|from where (i|we)|relative"
        r"|compared|in relation)"
        r"|\bfrom my (point of view|perspective|viewpoint|position|view|side|angle)\b"
        r"|^from where (i am|i stand|i am standing)\b.*\bwhere (is|are)\b|\bo ?clock\b",
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
    (
        4,
        _P,
        r"(?<!right )(?<!correct )(?<!wrong )(?<!same )\b(route|path|directions|guidance"
        r"|instructions|navigation|itinerary)\b",
    ),
    (5, _P, r"\b(which|what) (way|door|corridor|hallway|path|route|exit|doorway) (leads|goes)\b"),
    (4, _P, r"^(the |a )?(road|way|route|path|directions?) (to|toward|into)\b"),
    (3, _P, r"\bthe (road|way) to\b|\b(go|get|reach|walk|head) (to|there)\b.*\bhow$"),
    (3, _P, r"\bwhere (to|next|now)\b"),
    (5, _P, r"\b(now|then|next) where$|\bwhere (to )?(now|next)$"),
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
    (
        5,
        _P,
        r"\bwhich way (do|should|must|shall|can) (i|we) (go|head|walk) (in order )?to (find|reach"
        r"|get)\b|\bvia\b",
    ),
    (4, _P, r"\bbetween (me|here|us) and\b|\brooms? (\w+ )?(lie|lies|are|is) between\b"),
    (3, _P, r"\bfrom (the |my |this |here )(\w+ ){0,3}to (the|my|your|its|a|that) "),
    (4, _P, r"\b(which|what) (room|door|hallway|corridor) (next|now|first|then)\b|\bthen where\b"),
    (4, _P, r"\b(tell|show|give|explain|describe)( me| us)? (the|a) way\b"),
    (3, _P, r"\b(plan|planning|chart|map out)\b"),
    (5, _P, r"\b(go|walk|head|move|turn) (in order )?(to|for) (get to|reach|arrive)\b"),
    # Choosing rooms to pass: "is it better to go through the kitchen or the hall"
    (
        5,
        _P,
        rf"\b(through|via|to|toward|into) (the )?({ROOM_WORDS}) or (through |via |to "
        r"|into )?(the )?"
        rf"({ROOM_WORDS})\b"
        r"|\b(better|faster|quicker|shorter|easier) to (go|walk|take|pass|head)\b",
    ),
    # Another way, or where to search: "is there a shorter way", "should i search upstairs".
    (
        5,
        _P,
        r"\b(shorter|quicker|faster|better|other|another|different|alternative|easier|safer)"
        r" (way|route|path)\b(?! (up|down|round"
        r"|around)\b)(?<!facing the other way)(?<!looking the other way)",
    ),
    (
        4,
        _P,
        r"\b(should|do|must|can|shall) (i|we) (search|explore|check|look) (upstairs|downstairs"
        r"|the|in|there|elsewhere|another|other|for)\b",
    ),
    (3, _P, r"\b(pass|cut) through\b|\b(leads?|goes) (to|toward)\b|\btraverse\b"),
    (4, _P, r"\b(which|what) rooms?\b.*\b(through|pass|cross|traverse)\b"),
    (5, _P, r"\b(on|along) (the|my|our) way\b(?! (back|out)\b)"),
    (2, _P, r"\bto reach (it|the|that|my)\b"),
    (3, _P, r"\bfrom (my|our) (current |present )?(position|location|place)\b"),
    (2, _P, r"\b(reaching|arriving|getting to|get to|arrive at|arrive to)\b"),
    (
        5,
        _P,
        rf"\bwhich (rooms|doors|room|door|doorway|hallway|corridor|exit|{ROOM_WORDS}) (should|do"
        r"|must"
        r"|can)"
        r" (i|we)\b(?! find)",
    ),
    # Which part of the house to go to or search next: "which room to search next".
    (
        6,
        _P,
        r"\b(which|what) (rooms|room|part of the house|part|area|place|floor|wing|corridor|hallway"
        rf"|{ROOM_WORDS}) (\w+ )?(to|should (i|we)|do (i|we)|must (i|we)|shall (i|we)|can (i|we))"
        r" (search|go|visit|check|look|explore|head|enter|try|take|move|walk)\b",
    ),
    # Route, step: the next action.
    (
        3,
        _S,
        r"\b(should|do|must|shall|can|need|(am i|are we) (supposed|meant|expected|required"
        r"|allowed)) (i|we|to) (need to |have to )?(turn|go|keep|continue"
        r"|stop|move|leave|enter|exit|take|cross|follow|walk|head|proceed|step|approach|advance"
        r"|back out|back away|get out"
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
        r"|can|need to|have to)) do\b(?!.*\b(when|once|after|if) (i|we) find\b)"
        r"|\bwhat (\w+ ){0,3}(want|need|would like|expect) (me|us) to do\b",
    ),
    (4, _S, r"\b(up|down|in|out|forward|ahead|straight|back|upstairs|downstairs) or not\b"),
    # What to do: "tell me what to do now", "next i must do what".
    (
        5,
        _S,
        r"\bwhat to do\b(?!.*\b(when|once|after|if) (i|we) find\b)"
        r"|\b(i|we) (should|must|can|need to|have to|shall) do what\b",
    ),
    # A bare command offered as a question: "back up a bit?", "go through the door now?"
    (
        3,
        _S,
        r"^(go|turn|move|step|walk|head|back up|back off|keep|continue|proceed|advance|stop|enter"
        r"|exit|climb|reverse|go back|cross)\b(?! (me|us)\b)(?!.*\b(how|what|which|where)\b)",
    ),
    (3, _S, r"\bwhich way now\b"),
    # One move through a door: "do i open this door", "go through the doorway now".
    (
        4,
        _S,
        rf"{_NOT_WH}.*\b(open|close|shut|pass|go through|walk through|get through|pass through"
        r"|enter"
        r"|use|take|cross|push|pull|go into|go out of|step through) (this|that|the|a) (\w+ )?(door"
        r"|doorway|gate|exit|entrance|opening|arch|archway|doors)\b",
    ),
    (3, _S, rf"{_NOT_WH}.*\b(go|walk|pass|get|cut|squeeze) through (here|there|this|that)\b"),
    # The move stated and offered for confirmation: "now i must go forward", "i go through?"
    (
        3,
        _S,
        rf"{_NOT_WH}.*{_NOT_AFTER}\b(i|we) (go|walk|pass|turn|move|step|head|continue|enter|exit"
        r"|open|take"
        r"|cross|keep going|go back) ((to the )?(left|right|through|in|inside|out|forward"
        r"|straight|back|ahead|on|around|up|down|into|upstairs|downstairs)\b|(this|that|the)"
        r" (\w+ )?(door|doorway|exit|stairs|corridor|hallway)\b)(?! to\b)",
    ),
    (
        3,
        _S,
        rf"{_NOT_WH}.*\b(i|we) (should|must|need to|have to|shall|can) (turn|go|keep"
        r"|continue|stop|move|leave|enter|exit|take|cross|walk|head|proceed|step|open|back up"
        r"|rotate|go back)\b(?! to\b)",
    ),
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
    # Bare actions: "turn?", "straight on?", "forward, left, right or stop?", "left or right?"
    (6, _S, r"^(left|right|straight|forward|back)( or (left|right|straight|forward|back|stop))+$"),
    # A bare move along a part of the house: "up the stairs or not?"
    (
        4,
        _S,
        r"^(up|down|in|into|out|through|across|past|around|along) (the|this|that) \w+( or not"
        r"| now)?$",
    ),
    # A bare move with its size, or a bare "and now?": "forward two meters?", "up?"
    (
        5,
        _S,
        r"^((go|turn|move|step|walk) )?(left|right|straight|forward|back|ahead|up|down|upstairs"
        r"|downstairs|in|inside|out|through|around)( (a bit|a little|slightly|more|again|\w+"
        r" (meters?|steps?|feet|degrees|m)))?$|^(and )?(now|then|after that|afterwards)$",
    ),
    (
        4,
        _S,
        r"^((turn|go|keep) )?(left|right|straight|forward|back|stop|turn|next|action|move|continue"
        r"|carry on|proceed|straight on|keep going)( now| here| then| again)?$|\b(forward|straight"
        r"|ahead)\b.*\b(left|right)"
        r"\b.*\b(stop|left|right)\b",
    ),
)
