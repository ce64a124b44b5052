"""Spelling of navigator questions: contractions, chat spellings and typo correction.

People and models type questions with contractions ("what's"), chat spellings ("u", "wat")
and typos ("colr", "rigth"). The cues look for exact words, so a typo in a keyword hides the
question's intent; :func:`corrected` repairs such words without touching real words.
"""

from __future__ import annotations

from functools import cache

from vlln.world.catalogue.registry import default_catalogue

CONTRACTIONS: dict[str, str] = {
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
    "you've": "you have",
    "you'll": "you will",
    "you'd": "you would",
    "we're": "we are",
    "we've": "we have",
    "they're": "they are",
    "i'd": "i would",
    "it'll": "it will",
    "won't": "will not",
    "can't": "cannot",
    "cant": "cannot",
    # "isn't", "isnt" -> "is not", and so on for every auxiliary.
    **{
        f"{verb}{ending}": f"{verb} not"
        for verb in (
            [
                "is",
                "are",
                "was",
                "were",
                "do",
                "does",
                "did",
                "have",
                "has",
                "had",
                "should",
                "would",
                "could",
                "must",
                "need",
            ]
        )
        for ending in ("n't", "nt")
    },
    "let's": "let us",
    "whats": "what is",
    "way's": "way is",
    "one's": "one is",
    "infront": "in front",
    "wheres": "where is",
    "thats": "that is",
}

CHAT_SPELLINGS: dict[str, str] = {
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
    across action actions advance agent aligned already approach arrived attached azimuth
    bearing beneath between biggest bookshelf bored bright building built camera candidate
    category center centered chair check checked checkered choice circular clockwise closed
    constructed contain contains correspond count declare depict depicted describing design
    detected different display displayed distinguish doorway dresser empty enumerate episode
    explain explore farther fastest favorite field finish fireplace floral follow forgot
    frame furniture further house hungry identical identify identity illustrate image inside
    intended journey landmarks leaning length locate locked match matches matte middle
    nearest nightstand north number observe observed opposite orientation oriented output
    painted patterned perspective picture porcelain portray printed provide qualify quickest
    rectangular relation relationship remember remind repeat report represent requested
    required return rotate rotation round satisfy screen search searched second shortest
    show showing shown simulation sleepy slightly south specified specify spotted square
    staring stopped stored stripes surface surrounding surroundings taller thicker thinner
    thirsty tired traverse turned unique upper viewpoint visit visited walking wanted
    wardrobe weather whether window windows windowsill within wonder wondering written
    current about colour neighbour centre favourite
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
    described describing describes question quick roughly reached mate dude bro buddy pal
    lol heavy weigh weighs weight
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
    current currently present while painting paintings remind instruction
    short thin thick form block brow heard herd lake lime load neat nest self font sift sliver
    torn wife fade thought compute computed shade talk talking start wander fellow fame
    store forget
    """
    )
)


@cache
def _vocabulary() -> frozenset[str]:
    """Every word taken as correctly spelt: keywords, common words and object names."""
    catalogue = default_catalogue()
    names = [*catalogue.names, *catalogue.aliases]
    objects = {word for name in names for word in name.split()}
    return _KNOWN_WORDS | frozenset(objects) | frozenset(f"{word}s" for word in objects)


@cache
def corrected(word: str) -> str:
    """The word a typo most likely meant, or the word itself.

    Only unknown words of three letters or more that are not a known word with an ending
    ("pointed") are corrected: to any known word by a swap of two neighbouring letters ("teh"
    -> "the", "chiar" -> "chair"), else (four letters or more) to a keyword one edit away (two
    for words of seven letters or more) that starts with the same letter (or the same two,
    swapped). A changed letter counts as one edit only when its key touches the right one or
    both are vowels, since typos are slips of the finger. Ties keep the word unchanged, so a
    correction is never a guess; most unknown words are real words that no keyword is close to.
    """
    vocabulary = _vocabulary()
    if len(word) < 3 or word in vocabulary or word.isdigit() or _is_inflection(word, vocabulary):
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
    meant = {CHAT_SPELLINGS.get(keyword, keyword) for keyword in best}  # "colour" is "color"
    return meant.pop() if len(meant) == 1 else word


_SUFFIXES = ("s", "es", "ed", "d", "ing", "er", "est", "r", "st")


def _is_inflection(word: str, vocabulary: frozenset[str]) -> bool:
    """Whether ``word`` is a known word with an ending ("pointed", "starts", "shorter",
    "stopping"): a real word, not a typo, even when it is one letter from a keyword."""
    for suffix in _SUFFIXES:
        stem = word.removesuffix(suffix)
        if stem == word or len(stem) < 3:
            continue
        if stem in vocabulary or f"{stem}e" in vocabulary or _undoubled(stem) in vocabulary:
            return True
    return False


def _undoubled(stem: str) -> str:
    """ "stopp" -> "stop": the doubled final consonant of a short vowel before an ending."""
    single = stem[:-1]
    short_vowel = len(single) >= 3 and single[-2] in _VOWELS and single[-3] not in _VOWELS
    return single if stem[-1] == stem[-2] and short_vowel else stem


_KEYBOARD_ROWS = (("qwertyuiop", 0.0), ("asdfghjkl", 0.25), ("zxcvbnm", 0.75))  # (keys, shift)
_VOWELS = frozenset("aeiouy")


def _keyboard_neighbours() -> frozenset[tuple[str, str]]:
    """Pairs of letters whose keys touch on a QWERTY keyboard."""
    position = {
        key: (row, column + shift)
        for row, (keys, shift) in enumerate(_KEYBOARD_ROWS)
        for column, key in enumerate(keys)
    }
    return frozenset(
        (a, b)
        for a, (row_a, x_a) in position.items()
        for b, (row_b, x_b) in position.items()
        if (row_a == row_b and abs(x_a - x_b) == 1)
        or (abs(row_a - row_b) == 1 and abs(x_a - x_b) < 1)
    )


_NEIGHBOURS = _keyboard_neighbours()


def _substitution_cost(a: str, b: str) -> int:
    """A slip to a neighbouring key or another vowel is one edit; any other letter is two, so
    that real words one letter apart ("shade", "shape") are not taken for typos."""
    if a == b:
        return 0
    return 1 if (a, b) in _NEIGHBOURS or (a in _VOWELS and b in _VOWELS) else 2


def _edit_distance(a: str, b: str, limit: int) -> int:
    """Optimal-string-alignment distance (a swap of neighbours is one edit), capped."""
    previous2: list[int] = []
    previous = list(range(len(b) + 1))
    for i in range(1, len(a) + 1):
        current = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            cost = _substitution_cost(a[i - 1], b[j - 1])
            current[j] = min(previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost)
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                current[j] = min(current[j], previous2[j - 2] + 1)
        if min(current) > limit:
            return limit + 1
        previous2, previous = previous, current
    return previous[-1]
