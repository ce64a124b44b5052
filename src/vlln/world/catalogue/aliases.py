"""Earlier category names and the reference's names for the same things.

The catalogue uses the reference benchmark's category names (its ``normal_category.json``, the
cleaned Matterport3D names), so that episodes and scene summaries of either kind mean the same
objects. Names that vlln used before, or that people commonly say, stay readable: every place
that reads a category name (episode files, scene summaries, questions to the oracle) maps an
alias to its category with :func:`canonical_category`.
"""

from __future__ import annotations

ALIASES: dict[str, str] = {
    "sofa": "couch",
    "kitchen counter": "counter",
    "trash can": "garbage",
    "suitcase": "luggage",
    "laundry basket": "hamper",
    "radiator": "heater",
    "chest of drawers": "drawer",
    "exercise bike": "excercise equipment",
    "exercise ball": "excercise equipment",
    "exercise equipment": "excercise equipment",
}


def canonical_category(name: str) -> str:
    """The catalogue's name for ``name``: itself, or the category an alias stands for."""
    return ALIASES.get(name, name)


def aliases_of(categories: set[str]) -> dict[str, str]:
    """The aliases (alias -> category) that stand for one of ``categories``."""
    return {alias: name for alias, name in ALIASES.items() if name in categories}
