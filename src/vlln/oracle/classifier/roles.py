"""House words read by their role: any catalogue object as one word, any room as another.

A question's type rarely depends on which object or room it names: "Is the towel blue?" and
"Is the piano blue?" are both about a colour. With the names replaced by role words the
classifier also sees "is the <object> <colour>", so what it learnt from one object carries to
objects it saw seldom. The vocabularies are the house's own (the catalogue with its aliases,
the room types, the palette, the materials), so this is a look-up, not a language rule.
"""

from __future__ import annotations

from functools import cache

from vlln.oracle.classifier.entities import MATERIAL_SYNONYMS, ROOM_SYNONYMS, object_names
from vlln.world.materials import COLORS

# Role words: no English word, so they never meet a real one in the features.
OBJECT, ROOM, COLOUR, MATERIAL = "zzobject", "zzroom", "zzcolour", "zzmaterial"


@cache
def role_of_phrase() -> dict[str, str]:
    """Each house phrase (one to three words) and its role word. An object name that is also
    a room ("toilet") reads as an object: the question names the thing it looks for."""
    names = object_names()
    objects = names | {f"{name}s" for name in names} | {f"{name}es" for name in names}
    roles: dict[str, str] = {}
    for phrases, role in (
        (objects, OBJECT),
        (ROOM_SYNONYMS, ROOM),
        (COLORS, COLOUR),
        (MATERIAL_SYNONYMS, MATERIAL),
    ):
        for phrase in phrases:
            roles.setdefault(phrase.lower(), role)
    return roles


@cache
def _longest_phrase() -> int:
    return max(len(phrase.split()) for phrase in role_of_phrase())


def with_roles(words: list[str]) -> list[str]:
    """``words`` with each house phrase, longest first from the left, replaced by its role."""
    roles = role_of_phrase()
    longest = _longest_phrase()
    out: list[str] = []
    i = 0
    while i < len(words):
        for size in range(min(longest, len(words) - i), 0, -1):
            role = roles.get(" ".join(words[i : i + size]))
            if role is not None:
                out.append(role)
                i += size
                break
        else:
            out.append(words[i])
            i += 1
    return out
