"""Whether a question sets two candidates of the target's kind against each other by name:
"left cabinet or right cabinet?", "coffee table or side table?", "the green leafy one or the
cactus?", "above the counter or below it?", "left or right tv".

The paper's route question "left or right?" names no object, and its attribute questions set
values, not things, against each other ("is the sofa blue or grey?", "is it a chair or a
sofa?" asks what it is), so none of them reads as named alternatives.
"""

from __future__ import annotations

import re

# Catalogue words that name no candidate on their own ("side table" does, "side" does not).
_NOT_NOUNS = "of can side floor light range switch stand control air water body game"
NOT_NOUNS = frozenset(_NOT_NOUNS.split())
# What "left X or right X" names when it asks the way, not a candidate.
_ROUTE = "side hand turn way branch door doorway corridor hallway hall path exit room stairs "
_ROUTE_NOUNS = frozenset(f"{_ROUTE} staircase passage direction wing one".split())
# Words that set candidates apart by place, height, order or size.
_MARKS = (
    r"(left|right|upper|lower|top|bottom|front|back|first|second|higher|bigger|smaller|taller|"
    r"shorter|larger|nearer|closer|farther|further|near|far|big|small|little|tall|short|this|"
    r"that|other|next)"
)
_SAME_NOUN = re.compile(rf"\b{_MARKS} (\w+ )?(?P<noun>\w+) or (the )?{_MARKS} (\w+ )?(?P=noun)\b")
_AT = re.compile(
    r"\b(on|in|at|by|near|under|to|from|of|next to|beside) (the |a |an )?(\w+ )?\w+,? or\b"
)
_SIDE_NOUN = re.compile(r"\b(left|right) or (the )?(left|right) (?P<noun>\w+)\b")
_ONE_OR = re.compile(r"\bthe (\w+ ){0,3}ones? (.* )?or (the|this|that|by|in|on|with)\b")
_PLACES = r"(above|below|under|over|on top of|beneath|underneath|upstairs|downstairs)"
_PLACE_OR = re.compile(rf"\b{_PLACES} (the \w+( \w+)? )?or {_PLACES}\b")
_ARTICLE_OR = re.compile(r"\b(a|an) \w+ or (a|an) \w+\b")


def named_alternatives(words: str, nouns: frozenset[str]) -> bool:
    """Whether ``words`` (normalised) offer two candidates, each named by a noun of ``nouns``
    (the catalogue's words) or by "one", by a side or a place (module doc)."""
    if " or " not in f" {words} ":
        return False
    named = nouns - NOT_NOUNS
    same = _SAME_NOUN.search(words)
    noun = "" if same is None else same["noun"]  # "front-loading or top-loading" is a kind
    if (noun and noun not in _ROUTE_NOUNS and not noun.endswith("ing")) or _ONE_OR.search(words):
        return True
    side = _SIDE_NOUN.search(words)
    if (side is not None and side["noun"] in named) or _PLACE_OR.search(words):
        return True
    if _ARTICLE_OR.search(words) or _AT.search(words):
        return False  # "is it a chair or a sofa?" asks what it is; "on the bed or the sofa?"
    before, _, after = words.partition(" or ")
    if not re.match(r"(the|this|that) ", after):  # "coffee table or side table?": its kind
        return False
    return names_thing(" ".join(before.split()[-3:]), named) and names_thing(
        " ".join(after.split()[:4]), named
    )


def names_thing(words: str, nouns: frozenset[str]) -> bool:
    """Whether ``words`` hold a noun of ``nouns`` (a plural too)."""
    return any(w in nouns or w.rstrip("s") in nouns for w in words.split())
