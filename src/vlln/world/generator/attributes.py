"""The words an oracle can say about a generated instance, and its one-sentence caption.

Everything here is read off the drawn style and the placement, so the words are true of the
rendered object by construction: a "red wooden chair" is drawn red with the wood material.
"""

from __future__ import annotations

from vlln.world.catalogue.base import Category, Placement, Style
from vlln.world.materials import MATERIAL_TEXTURE
from vlln.world.model import Attributes

# Adjectives for materials in captions ("a wooden chair"); "plain" paint is not mentioned.
MATERIAL_ADJECTIVE: dict[str, str] = {
    "plain": "",
    "wood": "wooden",
    "fabric": "fabric",
    "metal": "metal",
    "marble": "marble",
    "leather": "leather",
    "glass": "glass",
    "plastic": "plastic",
    "ceramic": "ceramic",
    "tile": "tiled",
    "carpet": "carpeted",
    "foliage": "leafy",
}


def placement_words(placement: Placement, support_category: str = "") -> str:
    """How an instance is placed, e.g. ``"against the wall"`` or ``"on the table"``."""
    if placement is Placement.ON_SURFACE and support_category:
        return f"on the {support_category}"
    return placement.value


def describe(
    category: Category, style: Style, placement: str, room_type: str
) -> tuple[str, Attributes, str]:
    """``(fine category, attributes, caption)`` of one instance."""
    fine = category.shapes[style.shape]
    attributes = Attributes(
        color=style.color,
        material=style.material,
        texture=MATERIAL_TEXTURE.get(style.material, ""),
        shape=style.shape,
        size=style.size_word,
        placement=placement,
    )
    return fine, attributes, caption(fine, attributes, room_type)


def caption(fine_category: str, attributes: Attributes, room_type: str) -> str:
    """E.g. ``"A large red wooden dining chair at the table in the dining room."``"""
    words = [attributes.size, attributes.color, MATERIAL_ADJECTIVE.get(attributes.material, "")]
    noun = fine_category
    # Skip words the fine category already says ("a wooden wooden stool").
    adjectives = [w for w in words if w and w not in noun.split()]
    phrase = " ".join([*adjectives, noun])
    article = "An" if phrase[0] in "aeiou" else "A"
    if attributes.placement == Placement.CORNER.value:
        where = f"in a corner of the {room_type}"
    else:
        where = f"{attributes.placement} in the {room_type}"
    return f"{article} {phrase} {where}."
