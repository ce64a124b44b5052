"""Normalising a navigator's question so that simple patterns can read it.

Questions are typed by people and models alike: mixed case, contractions, chat spellings and
typos. :func:`normalise` turns them into lower-case words separated by single spaces, one
sentence a line, with spelling repaired by :mod:`vlln.oracle.spelling` ("what's" -> "what is",
"u" -> "you", "colr" -> "color"). :func:`rephrase` then undoes what hides a question's frame:
politeness, hedges and negation ("isn't it behind me"), embedded questions ("whether this is
the target"), a subject put first ("the mug, is it on the counter") and non-native word order
("how I can go").
"""

from __future__ import annotations

import re
from functools import cache

from vlln.oracle.spelling import CHAT_SPELLINGS, CONTRACTIONS, corrected
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

_AUX = r"(can|should|must|could|would|will|shall|do|need to|have to|am|are)"

# (pattern, replacement), applied in order to normalised text.
_REWRITE_RULES: tuple[tuple[str, str], ...] = (
    (r"\bnext too\b", "next to"),
    # Politeness and hedging adverbs say nothing about the intent, wherever they stand.
    (r" ?\b(?:please|kindly|just|really|actually|basically|simply|literally)\b", ""),
    # Fillers and politeness wrappers say nothing about the intent.
    (r"^(sorry|excuse me|pardon me)( if| for)?\b[\w ]*? (question|asking|bothering)( but)? ", ""),
    (
        r"^((so|and|ok|okay|well|then|hmm|um|uh|erm|hey|hi|yo|mate|dude|bro|buddy|pal|please"
        r"|kindly|sorry|oh|alright|wait"
        r"|excuse me|dear me|pray tell|quick question|one question|a question|question|query) )+",
        "",
    ),
    # Narrative before an embedded question: "i went through the hall can you tell me ...".
    (
        r"^(.*\b(?<!how )(?<!why ))?((can|could) you tell me|i (am|was) wondering|i wonder"
        r"|do you know)\b ?(?=(whether|if|where|which|what|how|is|are|am|does|do|did|should|can"
        r"|could|would|will|has|have)\b)",
        "",
    ),
    (
        r"^((can|could|would|will) you (please |kindly )?)?(tell me|let me know|say)( please)?"
        r"(?= (whether|if|where|which|what|how|who|when|is|are|am|does|did|should|can|could"
        r"|would|will|has|have|on|in)\b) ?",
        "",
    ),
    (
        r"^(i (would like|want|wish|need) to know|i (wonder|am wondering|was wondering)"
        r"|do you know|any idea|i ask you|my question is)( please)? ?",
        "",
    ),
    (r"( (please|thanks|thank you|then|now please|do you think|you think|if you can))+$", ""),
    # A negated question asks what the plain one asks: "is not it behind me", "am i not
    # close", "are not i in the kitchen" -> "is it behind me", "am i close", "am i in ...".
    (
        r"^((?:is|are|am|was|were|do|does|did|should|shall|can|could|would|will|have|has|must)"
        r"(?: (?:i|it|this|that|we|you|they|the \w+))?) not\b",
        r"\1",
    ),
    (r"^are i\b", "am i"),
    # A negated statement with a tag: "you do not mean this chair, do you" -> "do you mean
    # this chair".
    (
        r"^(you|i|we|they|it) (do|does|did|can|will|should|would)(?: not)? (.+?) (?:do|does|did"
        r"|can|will|should|would|is|are) (?:you|i|we|they|it)(?: not)?$",
        r"\2 \1 \3",
    ),
    # Embedded yes/no question: "whether the lamp i see is the target" -> "is the lamp ...",
    # "whether i should go through it" -> "should i go through it".
    (r"^(?:whether|if) (i|we) (should|can|must|could|would|will|shall|am|are) ", r"\2 \1 "),
    (
        r"^(?:whether|if) ((?:this|that|these|those|the)(?: [\w ]+?)?|it|they) (is|are|was) ",
        r"\2 \1 ",
    ),
    # Hedges before a statement offered for confirmation: "i think this is the lamp, yes".
    (r"^(i think|i guess|i believe|i suppose|maybe|perhaps) (?=(this|that|it|here)\b)", ""),
    (
        r"^(i forgot|i do not remember|i cannot remember|i am not sure|to be sure|checking"
        r"|remind me|i am (pretty |quite |fairly )?sure)( again)? "
        r"(?=(the|this|that|it|is|are|what|which|where|how)\b)",
        "",
    ),
    # A subject put first and taken up by a pronoun: "the mug, is it on the counter" -> "is
    # the mug on the counter", "the chair, does it have arms" -> "does the chair have arms".
    (
        r"^((?:the|this|that|these|those)(?: (?!(?:what|which|where|how|is|are|was)\b)\w+)+?)"
        r" (is|are|was|does|do|did|has|have) (?:it|they) ",
        r"\2 \1 ",
    ),
    # The navigator named in the third person: "should the agent move" -> "should i move".
    (
        r"\b(should|can|could|must|do|did|will|would|shall) (?:the )?(?:agent|robot|navigator)\b",
        r"\1 i",
    ),
    (r"\bdoes (?:the )?(?:agent|robot|navigator)\b", "do i"),
    (r"\b(?:is|was) the (?:agent|robot|navigator)\b", "am i"),
    (r"\bthe (?:agent|robot|navigator) is\b", "i am"),
    (r"\b(?:the )?(?:agents|robots|navigators)\b", "my"),
    (r"\b(?:the )?agent (?=(?:pose|position|location|heading|room|state|coordinates)\b)", "my "),
    (r"\bthe (?:agent|robot|navigator)\b", "me"),
    # An object named by where the navigator is: "the stool i am near" -> "the stool in front
    # of me", so it reads as a candidate, not as the navigator's progress.
    (
        r"\b(the|this|that) (?!(?:way|direction|side|room)\b)(\w+) (?:that |which )?i am (?:now "
        r"|currently )?(?:(?:standing|sitting|stopped) )?(?:near|next to|at|beside|by|facing"
        r"|looking at|pointing at|in front of|close to)\b",
        r"\1 \2 in front of me",
    ),
    (
        r"\b(the|this|that) (\w+) (?:that |which )?i am (?:now |currently )?(?:(?:standing|sitting"
        r"|lying) )?on\b",
        r"\1 \2 under me",
    ),
    # The room the navigator stands in is "this" room: "is the mirror in the bathroom i am in
    # the target" -> "is the mirror in this bathroom the target".
    (
        r"\b(?:the|this|that) (\w+) (?:that |which )?(?:i am|we are) (?:now |currently )?in\b",
        r"this \1",
    ),
    # A subject put first and asked about after: "the basket, what is inside it" -> "what is
    # inside the basket", "the bath mat, what colour" -> "what colour the bath mat".
    (
        r"^((?:the|this|that)(?: (?!(?:what|which|where|how|is|are|has|have|does|do|can)\b)\w+)"
        r"{1,4}?) "
        r"((?:what|which|where|how)\b.*?)(?: (?:it|they|them))?$",
        r"\2 \1",
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
    # A statement asked as a question: "the guitar is acoustic or electric" -> "is the guitar
    # acoustic or electric".
    (
        r"^((?:the|this|that|these|those)(?: (?!(?:what|which|where|how|is|are|was|i|you|we)\b)"
        r"\w+){1,4}) (is|are|was) (?!(?:it|not|that|this)\b)",
        r"\2 \1 ",
    ),
    (
        r"\b(confirm|verify|check)( for me)? (?:whether|if|that) "
        r"(this|that|it|the [\w ]+?) (is|are|was) ",
        r"\1 \4 \3 ",
    ),
    # Subject before auxiliary: "how i can go" -> "how can i go", "which room i am in",
    # "where i have to go" -> "where do i have to go", "what i do next" -> "what do i do
    # next"; but "from where i am, where is it" sets the scene for the question after it.
    (
        r"^((?:in |to |from |toward |towards )?(?:how|where|(?:what|which) (?:way|room|side"
        r"|direction|place|area)|what|why|when)) (i|we) (need to|have to|want to|do|go|get|turn"
        r"|find|look|search|reach|walk|head|move)\b",
        r"\1 do \2 \3",
    ),
    (
        r"^((?:in |to |from |toward |towards )?(?:how|where|(?:what|which) (?:way|room|side"
        rf"|direction|place|area)|what|why|when)) (i|we) {_AUX}\b(?!.*\b(where|which|what|how)\b)",
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
    -> "how can i go", "the chair you want" -> "the target chair". Each sentence (line) is
    rephrased on its own; sentences left empty are dropped."""
    sentences = []
    for sentence in text.split("\n"):
        for pattern, replacement in _REWRITES:
            sentence = pattern.sub(replacement, sentence).strip()
        if sentence:
            sentences.append(sentence)
    return "\n".join(sentences)


_TOKEN = re.compile(r"[a-z0-9]+(?:'[a-z]+)?")
# After a noun, "'s" before a determiner is "is" ("which room's the desk in"), not a possessive.
_IS_AFTER = frozenset(("the", "a", "an", "it", "this", "that", "my", "your", "there", "not"))
_HAS_AFTER = frozenset(("got", "been"))  # "which room's got the piano"


def normalise(text: str) -> str:
    """Lower-case words separated by single spaces, with spelling and typos fixed, one
    sentence a line: "I'm at the fridge. Is it the one?" -> "i am at the fridge\nis it the
    one". A question's frame ("is it ...") is then at the start of its own line. Object
    names of several words are joined into one ("floor_lamp")."""
    lowered = text.lower().replace("\u2019", "'").replace("`", "'")
    sentences = (_sentence_words(sentence) for sentence in _SENTENCE_END.split(lowered))
    joined = "\n".join(sentence for sentence in sentences if sentence)
    return _object_names().sub(lambda name: name.group().replace(" ", "_"), joined)


@cache
def _object_names() -> re.Pattern[str]:
    """Object names of several words, which :func:`normalise` joins with "_" into one word
    ("the floor_lamp"), so that a pattern for "the" and a noun takes the whole name and the
    "kitchen" of a "kitchen_island" is no room."""
    catalogue = default_catalogue()
    words = [*catalogue.names, *catalogue.aliases]
    names = sorted((n for n in words if " " in n), key=len, reverse=True)
    return re.compile(r"\b(" + "|".join(re.escape(n) for n in names) + r")(s|es)?\b")


# A full stop, question or exclamation mark or semicolon ends a sentence when a space or the
# end of the text follows it and a single letter does not precede it ("3.5 m" and "e.g. the
# bed" do not end one).
_SENTENCE_END = re.compile(r"(?<!\b[a-z])[.!?;]+(?=\s|$)")


def _sentence_words(sentence: str) -> str:
    expanded: list[str] = []
    tokens = _TOKEN.findall(sentence)
    for position, token in enumerate(tokens):
        following = tokens[position + 1] if position + 1 < len(tokens) else ""
        if token.endswith("'s") and token not in CONTRACTIONS:
            if following in _HAS_AFTER:
                token = f"{token[:-2]} has"
            elif following in _IS_AFTER:
                token = f"{token[:-2]} is"
        expanded.extend(CONTRACTIONS.get(token, token).split())
    words = []
    for word in expanded:
        fixed = corrected(CHAT_SPELLINGS.get(word.replace("'", ""), word.replace("'", "")))
        words.append(CHAT_SPELLINGS.get(fixed, fixed))  # a typo of "colour" was corrected to it
    return " ".join(words)
