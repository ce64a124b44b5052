"""What a detector mistakes for what: look-alike categories, colours, materials and sizes.

Categories are the object catalogue's names. A category's look-alikes are every other member
of each group in :data:`LOOKALIKE_GROUPS` that holds it, so the relation is symmetric (a stool
taken for a chair means a chair may be taken for a stool). A colour's look-alikes are the
:data:`COLOR_NEIGHBOURS` named colours nearest to it in linear RGB (``vlln.world.materials``),
so "red" is misread as a red-ish colour, never as "teal".
"""

from __future__ import annotations

import math

from vlln.world.materials import COLORS

# Groups of catalogue categories a detector confuses with each other (shape and use alike).
LOOKALIKE_GROUPS: tuple[tuple[str, ...], ...] = (
    ("chair", "armchair", "stool"),
    ("armchair", "couch"),
    ("stool", "ottoman", "beanbag"),
    ("bench", "ottoman"),
    ("table", "desk", "coffee table", "side table", "kitchen island"),
    ("side table", "nightstand"),
    ("counter", "kitchen island"),
    ("cabinet", "drawer", "dresser", "nightstand", "wardrobe"),
    ("bookshelf", "shelf", "shoe rack", "tv stand"),
    ("bed", "crib"),
    ("table lamp", "floor lamp"),
    ("cup", "bowl", "fruit bowl", "plate"),
    ("vase", "bottle"),
    ("kettle", "teapot", "coffee machine"),
    ("tv", "computer monitor", "picture", "mirror"),
    ("laptop", "keyboard"),
    ("microwave", "toaster"),
    ("dishwasher", "washing machine"),
    ("refrigerator", "wardrobe"),
    ("rug", "bath mat"),
    ("basket", "hamper", "garbage", "box"),
    ("bathtub", "shower"),
    ("bicycle", "excercise equipment"),
    ("excercise equipment", "treadmill"),
    ("backpack", "luggage"),
    ("oven", "microwave", "dishwasher"),
    ("clothes dryer", "washing machine"),
    ("footstool", "ottoman"),
    ("cushion", "pillow"),
    ("blanket", "sheet", "towel"),
    ("blinds", "curtain"),
    ("switch", "socket", "plug"),
    ("hook", "hanger", "coat rack"),
    ("vanity", "sink"),
    ("countertop", "counter", "kitchen island"),
    ("stand", "side table"),
    ("blackboard", "tv", "picture"),
    ("water heater", "water cooler"),
    ("air conditioner", "heater"),
    ("pool table", "table"),
    ("cart", "shelf"),
)

# Materials that look alike under indoor light.
MATERIAL_LOOKALIKES: dict[str, tuple[str, ...]] = {
    "plain": ("plastic", "ceramic"),
    "wood": ("leather", "plain"),
    "fabric": ("leather", "carpet"),
    "metal": ("glass", "plastic"),
    "marble": ("ceramic", "tile"),
    "leather": ("fabric", "wood"),
    "glass": ("plastic", "metal"),
    "plastic": ("plain", "glass"),
    "ceramic": ("marble", "plastic"),
    "tile": ("marble", "ceramic"),
    "carpet": ("fabric",),
    "foliage": ("fabric",),
}

# Relative sizes are misjudged by one step.
SIZE_LOOKALIKES: dict[str, tuple[str, ...]] = {
    "small": ("medium",),
    "medium": ("small", "large"),
    "large": ("medium",),
}

COLOR_NEIGHBOURS = 3
"""How many of the nearest named colours a colour is misread as."""


def category_lookalikes(category: str) -> tuple[str, ...]:
    """The categories ``category`` may be reported as instead, in table order (none for a
    category outside every group)."""
    found: list[str] = []
    for group in LOOKALIKE_GROUPS:
        if category in group:
            found += [other for other in group if other != category and other not in found]
    return tuple(found)


def _nearest_colors(count: int) -> dict[str, tuple[str, ...]]:
    table = {}
    for name, rgb in COLORS.items():
        others = sorted(
            (math.dist(rgb, other_rgb), other)
            for other, other_rgb in COLORS.items()
            if other != name
        )
        table[name] = tuple(other for _, other in others[:count])
    return table


COLOR_LOOKALIKES: dict[str, tuple[str, ...]] = _nearest_colors(COLOR_NEIGHBOURS)
