"""Named colours and materials.

Colours are the words an oracle speaks ("a white chair"), each with one linear-RGB value.
Materials are rendered as visibly different procedural textures by the shader; their index in
:data:`MATERIALS` is what the mesh stores per vertex, so the order here is part of the
renderer's contract (append new materials at the end).
"""

from __future__ import annotations

from vlln.errors import ConfigError

Rgb = tuple[float, float, float]

COLORS: dict[str, Rgb] = {
    "white": (0.92, 0.92, 0.90),
    "black": (0.05, 0.05, 0.05),
    "gray": (0.45, 0.45, 0.46),
    "light gray": (0.70, 0.70, 0.70),
    "dark gray": (0.22, 0.22, 0.23),
    "brown": (0.40, 0.24, 0.12),
    "dark brown": (0.20, 0.11, 0.05),
    "beige": (0.85, 0.78, 0.62),
    "red": (0.78, 0.10, 0.10),
    "orange": (0.92, 0.45, 0.10),
    "yellow": (0.93, 0.80, 0.15),
    "green": (0.20, 0.55, 0.22),
    "dark green": (0.08, 0.30, 0.12),
    "blue": (0.15, 0.30, 0.75),
    "navy": (0.07, 0.10, 0.35),
    "light blue": (0.55, 0.72, 0.90),
    "purple": (0.45, 0.20, 0.60),
    "pink": (0.93, 0.55, 0.65),
    "silver": (0.75, 0.76, 0.78),
    "gold": (0.83, 0.66, 0.22),
    "cream": (0.95, 0.91, 0.80),
    "teal": (0.10, 0.50, 0.50),
}

# Index = material id stored in the mesh; the shader switches on it.
MATERIALS: tuple[str, ...] = (
    "plain",  # untextured paint or plaster
    "wood",
    "fabric",
    "metal",
    "marble",
    "leather",
    "glass",
    "plastic",
    "ceramic",
    "tile",  # floor and wall tiles: a grid of grout lines
    "carpet",
    "foliage",  # leaves of plants
)

MATERIAL_INDEX: dict[str, int] = {name: i for i, name in enumerate(MATERIALS)}

# The texture word an oracle says for each material ("its texture is smooth").
MATERIAL_TEXTURE: dict[str, str] = {
    "plain": "smooth",
    "wood": "grained",
    "fabric": "woven",
    "metal": "brushed",
    "marble": "veined",
    "leather": "smooth",
    "glass": "glossy",
    "plastic": "glossy",
    "ceramic": "glossy",
    "tile": "tiled",
    "carpet": "soft",
    "foliage": "leafy",
}


def color_rgb(name: str) -> Rgb:
    """RGB of a named colour, with an error that lists the valid names."""
    try:
        return COLORS[name]
    except KeyError:
        raise ConfigError(
            f"unknown colour {name!r}; use one of: {', '.join(sorted(COLORS))}"
        ) from None


def material_index(name: str) -> int:
    """Mesh material id of a named material, with an error that lists the valid names."""
    try:
        return MATERIAL_INDEX[name]
    except KeyError:
        raise ConfigError(
            f"unknown material {name!r}; use one of: {', '.join(MATERIALS)}"
        ) from None
