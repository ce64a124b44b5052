"""Normalising a navigator's question so that simple patterns can read it.

Questions are typed by people and models alike: mixed case, contractions, chat spellings and
typos. :func:`normalise` turns them into lower-case words separated by single spaces, expands
contractions ("what's" -> "what is"), maps chat and British spellings ("u" -> "you",
"colour" -> "color"), drops punctuation, and corrects words that are not known English to a
pattern keyword within a small edit distance ("colr" -> "color", "rigth" -> "right").
:func:`rephrase` then undoes what hides a question's frame: politeness wrappers, embedded
questions ("whether this is the target") and non-native word order ("how I can go").
"""

from __future__ import annotations

import re
from functools import cache

from vlln.world.catalogue.registry import ROOM_TYPES, default_catalogue

# Canonical names of the rooms and materials a question may mention.
ROOM_SYNONYMS: dict[str, str] = {
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
MATERIAL_SYNONYMS: dict[str, str] = {
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

_CONTRACTIONS: dict[str, str] = {
    "what's": "what is",
    "where's": "where is",
    "which's": "which is",
    "how's": "how is",
    "it's": "it is",
    "that's": "that is",
    "there's": "there is",
    "here's": "here is",
    "who's": "who is",
    "i'm": "i am",
    "im": "i am",
    "i've": "i have",
    "ive": "i have",
    "i'll": "i will",
    "you're": "you are",
    "isn't": "is not",
    "isnt": "is not",
    "aren't": "are not",
    "don't": "do not",
    "dont": "do not",
    "doesn't": "does not",
    "doesnt": "does not",
    "didn't": "did not",
    "can't": "cannot",
    "cant": "cannot",
    "shouldn't": "should not",
    "let's": "let us",
    "whats": "what is",
    "way's": "way is",
    "one's": "one is",
    "infront": "in front",
    "wheres": "where is",
    "thats": "that is",
}

_CHAT_SPELLINGS: dict[str, str] = {
    "u": "you",
    "ur": "your",
    "r": "are",
    "wat": "what",
    "ths": "this",
    "tht": "that",
    "wht": "what",
    "wut": "what",
    "whr": "where",
    "wher": "where",
    "wer": "where",
    "wich": "which",
    "whch": "which",
    "shud": "should",
    "shld": "should",
    "sould": "should",
    "hw": "how",
    "pls": "please",
    "plz": "please",
    "thx": "thanks",
    "tat": "that",
    "colour": "color",
    "recognise": "recognize",
    "whereabouts": "where",
    "colours": "colors",
    "coloured": "colored",
    "grey": "gray",
    "favourite": "favorite",
    "metre": "meter",
    "metres": "meters",
    "nxt": "next",
    "fwd": "forward",
    "lft": "left",
    "rt": "right",
    "rm": "room",
    "tgt": "target",
    "obj": "object",
    "neighbour": "neighbor",
    "neighbours": "neighbors",
    "neighbouring": "neighboring",
    "centre": "center",
    "thru": "through",
    "towards": "toward",
}


def _words(text: str) -> list[str]:
    return text.split()


# Words the patterns key on: misspellings are corrected toward these.
_KEYWORDS: frozenset[str] = frozenset(
    _words(
        """
    color colors colored material materials made texture textured shape shaped size sized
    big bigger large larger small smaller tall height wide width long dimensions look looks
    like appearance describe description details features characteristics distinctive special
    kind type sort style room rooms kitchen bedroom bathroom toilet living dining study
    corridor storage hallway located location where which what should would could direction
    directions way route path reach arrive there left right turn turning straight forward
    ahead behind around backward backwards front facing face heading next near nearby next
    beside close closer closest far distance away meters steps target object goal thing item
    correct right same found find looking visible view sight see seeing guide lead navigate
    continue keep going stop upstairs downstairs through toward please answer wooden metal
    metallic plastic fabric leather glass ceramic marble adjacent neighbor surrounded under
    soft hard smooth rough shiny glossy striped pattern brown black white green yellow purple
    orange beige silver leave enter exit
    underneath above below sitting standing placed lying hanging mounted against corner wall
    floor table shelf counter progress track almost nearly getting relative compared pointing
    point orientation angle degrees moving move walk exactly information tell more another
    instance confirm verify guidance instructions navigation proceed composition position
    """
    )
)

# Common words that are never "corrected" even though they are one edit from a keyword.
_KNOWN_WORDS: frozenset[str] = _KEYWORDS | frozenset(
    _words(
        """
    a an the is are was were be been being am do does did done have has had having it its
    this that these those i me my mine you your we us our they them their he she his her
    to of in on at by for with from up down now here then than so and or not no yes can
    cannot could would will shall may might must go goes going went gone get got gets let
    us how why when who whom whose much many some any all one two three four five six
    seven eight nine ten still yet also too very really just only other else each every
    want need know think see saw seen looked find finding give tell told say said mean
    meant wait stay take come came try again ok okay hi hello hey thanks thank sorry
    good great fine well bad best better need help sure last first second third side sides
    described describing describes question quick roughly reached
    book books look lamp lamps lamp cup cups bed beds chair chairs sofa sofas desk desks
    rug rugs tv plant plants vase vases bowl bowls plate plates towel towels mirror mirrors
    picture pictures clock clocks pillow pillows stool stools bench benches couch couches
    bottle bottles basket baskets cabinet cabinets dresser lamp light lights window windows
    door doors sink sinks oven fridge piano guitar laptop speaker speakers curtain curtains
    bin trash wardrobe nightstand armchair ottoman radiator fireplace candle candles
    red blue green black white gray brown beige orange yellow purple pink silver gold cream
    teal navy dark light wood tile carpet foliage plain fan fans hat rat cat car bar bag
    bags box boxes lot lots bit set sit sat lie lay hang put gets got hit hot hole
    whole part area space house home place places spot thing things one ones
    left lest lift loft lend led let lot late later ate eat mat map cap tap
    back pack bank band bath both arm arms pot pots top mug mugs rag cot ask asked lost
    current currently present while painting paintings remind
    """
    )
)

_AUX = r"(can|should|must|could|would|will|shall|do|need to|have to|am|are)"

# (pattern, replacement), applied in order to normalised text.
_REWRITE_RULES: tuple[tuple[str, str], ...] = (
    # Fillers and politeness wrappers say nothing about the intent.
    (r"^(sorry|excuse me|pardon me)( if| for)?\b[\w ]*? (question|asking|bothering)( but)? ", ""),
    (
        r"^((so|and|ok|okay|well|then|hmm|um|uh|hey|hi|please|kindly|sorry|oh|alright|wait"
        r"|excuse me|dear me|quick question|one question|a question|question|query) )+",
        "",
    ),
    # Narrative before an embedded question: "i went through the hall can you tell me ...".
    (
        r"^(.*\b(?<!how )(?<!why ))?((can|could) you tell me|i (am|was) wondering|i wonder"
        r"|do you know)\b ?(?=(whether|if|where|which|what|how)\b)",
        "",
    ),
    (
        r"^((can|could|would|will) you (please |kindly )?)?(tell me|let me know|say)( please)?"
        r"(?= (whether|if|where|which|what|how|who|when)\b) ?",
        "",
    ),
    (
        r"^(i (would like|want|wish|need) to know|i (wonder|am wondering|was wondering)"
        r"|do you know|any idea|i ask you|my question is)( please)? ?",
        "",
    ),
    (r"( (please|thanks|thank you|then|now please|do you think|you think|if you can))+$", ""),
    # Embedded yes/no question: "whether the lamp i see is the target" -> "is the lamp ...".
    (
        r"^(?:whether|if) ((?:this|that|these|those|the)(?: [\w ]+?)?|it|they) (is|are|was) ",
        r"\2 \1 ",
    ),
    # Tag questions: "that is the chair, is not it" -> "is that the chair".
    (
        r"^((?:this|that|the)(?: [\w ]+?)?|it) (is|are|was) (.+?) (is not (it|that|this)"
        r"|is (it|that) not|are not they|yes|no|correct|or not"
        r"|(?<!the )(?<!my )(?<!your )(?<!its )(?<!to )(?<!on )(?<!at )(?<!turn )right)$",
        r"\2 \1 \3",
    ),
    # A wh-phrase left at the end or after its preposition: "the lamp is on which table",
    # "on which table the lamp is" -> "on which table is the lamp".
    (
        r"^(it|they|the [\w ]+?) (is|are|was) (in|on|near|next to|at|under|inside|beside"
        r"|on top of) (which|what)( \w+)?$",
        r"\3 \4\5 \2 \1",
    ),
    (
        r"^((?:in|on|near|next to|at|under|inside|beside|on top of) (?:which|what)(?: \w+)?)"
        r" (it|they|the [\w ]+?) (is|are)\b",
        r"\1 \3 \2",
    ),
    (
        r"\b(confirm|verify|check)( for me)? (?:whether|if|that) "
        r"(this|that|it|the [\w ]+?) (is|are|was) ",
        r"\1 \4 \3 ",
    ),
    # Subject before auxiliary: "how i can go" -> "how can i go", "which room i am in".
    (
        r"^((?:in |to |from )?(?:how|where|(?:what|which) (?:way|room|side|direction|place"
        rf"|area)|what|why|when)) (i|we) {_AUX}\b",
        r"\1 \3 \2",
    ),
    # "the chair you want" names the target itself, not an object in view.
    (
        r"\bthe (?!one\b)(\w+) (?:that |which )?(?:you want|you mean|i need|i want|i am looking"
        r" for|we are looking for|you are looking for|i need to find)\b",
        r"the target \1",
    ),
)
_REWRITES = [(re.compile(pattern), replacement) for pattern, replacement in _REWRITE_RULES]


def rephrase(text: str) -> str:
    """Normalised ``text`` with politeness wrappers and fillers dropped and the question's
    frame restored: "could you tell me whether this is it" -> "is this it", "how i can go"
    -> "how can i go", "the chair you want" -> "the target chair"."""
    for pattern, replacement in _REWRITES:
        text = pattern.sub(replacement, text).strip()
    return text


_TOKEN = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")


def normalise(text: str) -> str:
    """Lower-case words separated by single spaces, with spelling and typos fixed."""
    lowered = text.lower().replace("\u2019", "'").replace("`", "'")
    words: list[str] = []
    for token in _TOKEN.findall(lowered):
        token = _CONTRACTIONS.get(token, token)
        if " " in token:
            words.extend(token.split())
            continue
        token = token.replace("'", "")
        token = _CHAT_SPELLINGS.get(token, token)
        words.append(_corrected(token))
    return " ".join(words)


@cache
def _vocabulary() -> frozenset[str]:
    """Every word taken as correctly spelt: keywords, common words and object names."""
    objects = {word for name in default_catalogue().names for word in name.split()}
    return _KNOWN_WORDS | frozenset(objects) | frozenset(f"{word}s" for word in objects)


@cache
def _corrected(word: str) -> str:
    """The word a typo most likely meant, or the word itself.

    Only unknown words of three letters or more are corrected: to any known word by a swap of
    two neighbouring letters ("teh" -> "the", "chiar" -> "chair"), else (four letters or more)
    to a keyword one edit away (two for words of seven letters or more) that starts with the
    same letter (or the same two, swapped). Ties keep the word unchanged, so a correction is
    never a guess; most unknown words are real words that no keyword is close to.
    """
    vocabulary = _vocabulary()
    if len(word) < 3 or word in vocabulary or word.isdigit():
        return word
    swaps = {word[:i] + word[i + 1] + word[i] + word[i + 2 :] for i in range(len(word) - 1)}
    swapped = sorted(swaps & vocabulary)
    if swapped:
        return swapped[0] if len(swapped) == 1 else word
    limit = 2 if len(word) >= 7 else 1
    best: list[str] = []
    best_distance = limit + 1
    for keyword in _KEYWORDS:
        if abs(len(keyword) - len(word)) > limit or len(keyword) < 4:
            continue
        if keyword[0] != word[0] and keyword[:2] != word[1::-1]:
            continue
        distance = _edit_distance(word, keyword, limit)
        if distance > limit:
            continue
        if distance < best_distance:
            best, best_distance = [keyword], distance
        elif distance == best_distance:
            best.append(keyword)
    return best[0] if len(best) == 1 else word


def _edit_distance(a: str, b: str, limit: int) -> int:
    """Optimal-string-alignment distance (a swap of neighbours is one edit), capped."""
    previous2: list[int] = []
    previous = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        current = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = 0 if a[i - 1] == b[j - 1] else 1
            current[j] = min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                current[j] = min(current[j], previous2[j - 2] + 1)
        if min(current) > limit:
            return limit + 1
        previous2, previous = previous, current
    return previous[-1]
