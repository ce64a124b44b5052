"""Soft furnishings: cushions, blankets and sheets lying on furniture, and window blinds.

Cushions, blankets and sheets are low and flat so that the generator lays them on beds,
couches and shelves; blinds hang on outer walls like curtains.
"""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.bedroom import BEDDING_COLORS, TEXTILE_COLORS
from vlln.world.catalogue.parts import ring, shade, standing_on_floor
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

FABRIC = material_index("fabric")
PLASTIC = material_index("plastic")


def build_cushion(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A round cushion with a button in the middle, or a long round bolster with end caps."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "bolster":
        r, length = 0.09 * s, float(rng.uniform(0.42, 0.5)) * s
        b.cylinder((-length / 2, r, 0.0), r, length, color, mat, segments=12, axis="x")
        for x in (-length / 2 - 0.01, length / 2):
            b.cylinder((x, r, 0.0), r * 0.6, 0.01, shade(color, 0.8), mat, segments=8, axis="x")
        return ObjectModel(b.build())
    r, h = float(rng.uniform(0.19, 0.22)) * s, 0.1 * s
    b.cylinder((0.0, 0.0, 0.0), r, h * 0.5, color, mat, segments=14, radius_top=r * 0.98)
    b.cylinder((0.0, h * 0.5, 0.0), r * 0.98, h * 0.5, color, mat, segments=14, radius_top=r * 0.7)
    b.cylinder((0.0, h, 0.0), r * 0.12, 0.008, shade(color, 0.7), mat, segments=8)
    return ObjectModel(b.build())


def _folded_stack(
    b: MeshBuilder, style: Style, size: tuple[float, float], layers: int, layer_t: float
) -> float:
    """Layers of folded cloth with rounded front folds; returns the stack's height."""
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = size
    y = 0.0
    for k in range(layers):
        tone = shade(color, 1.0 - 0.06 * (k % 2))
        b.box((0.0, y + layer_t / 2, -0.01), (w, layer_t, d - 0.02), tone, mat)
        b.cylinder(
            (-w / 2, y + layer_t / 2, d / 2 - layer_t / 2 - 0.01),
            layer_t / 2,
            w,
            tone,
            mat,
            segments=6,
            axis="x",
        )
        y += layer_t
    return y


def build_blanket(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A folded blanket with a woven stripe across it, or a rolled one tied with a band."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "rolled":
        r, length = 0.1 * s, 0.5 * s
        b.cylinder((-length / 2, r, 0.0), r, length, color, mat, segments=12, axis="x")
        ring(b, (0.0, r, 0.0), r * 0.8, 0.015, 0.02, shade(color, 0.5), mat, "z", 12)
        for x in (-length / 2 - 0.002, length / 2):
            b.cylinder((x, r, 0.0), r * 0.9, 0.002, shade(color, 0.8), mat, segments=12, axis="x")
        return ObjectModel(b.build())
    w, d = float(rng.uniform(0.5, 0.6)) * s, 0.35 * s
    top = _folded_stack(b, style, (w, d), 3, 0.035 * s)
    stripe = shade(color, 0.55)
    for x in (-w * 0.3, w * 0.3):  # stripes over the top and down the folded front
        b.box((x, top + 0.001, 0.0), (0.04 * s, 0.002, d - 0.02), stripe, mat, faces="+y")
        b.box((x, top / 2, d / 2 + 0.002), (0.04 * s, top, 0.004), stripe, mat, faces="+z")
    return ObjectModel(b.build())


def build_sheet(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Bed sheets folded flat: one with a contrasting hem stripe, or a stack of several."""
    s = style.scale
    color = color_rgb(style.color)
    b = MeshBuilder()
    w, d = 0.38 * s, 0.3 * s
    layers = 1 if style.shape == "folded" else int(rng.integers(3, 5))
    top = _folded_stack(b, style, (w, d), layers * 2, 0.012 * s)
    hem = shade(color, 0.75)
    b.box((0.0, top + 0.001, d * 0.3), (w, 0.002, 0.03 * s), hem, FABRIC, faces="+y")
    return ObjectModel(b.build())


def build_blinds(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Venetian blinds (horizontal slats on cords) or a roller blind with a pull cord."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, h = float(rng.uniform(0.9, 1.3)) * s, 1.3 * s
    b = MeshBuilder()
    if style.shape == "roller":
        b.cylinder(
            (-w / 2 - 0.02, h - 0.04, 0.05), 0.04, w + 0.04, shade(color, 0.9), mat, 10, axis="x"
        )
        b.box((0.0, (h - 0.04) / 2 + 0.04, 0.09), (w, h - 0.08, 0.005), color, mat)
        b.box((0.0, 0.04, 0.09), (w + 0.02, 0.025, 0.02), shade(color, 0.7), mat)
        for x in (-w / 2 - 0.03, w / 2 + 0.03):  # brackets holding the roll to the wall
            b.box((x, h - 0.04, 0.045), (0.015, 0.08, 0.09), shade(color, 0.7), mat)
        b.box((w * 0.4, 0.02, 0.105), (0.006, 0.06, 0.006), color_rgb("white"), PLASTIC)
        return ObjectModel(standing_on_floor(b.build()))
    b.box((0.0, h - 0.025, 0.025), (w + 0.02, 0.05, 0.05), shade(color, 0.85), mat)
    n = int(h / 0.05)
    for k in range(n):
        y = 0.03 + k * (h - 0.08) / n
        b.box((0.0, y, 0.045), (w, 0.006, 0.05), color, mat, faces="+y-y+z-z")
    for x in (-w * 0.3, w * 0.3):
        b.box((x, (h - 0.05) / 2, 0.072), (0.004, h - 0.05, 0.004), shade(color, 0.7), PLASTIC)
    b.box((w / 2 - 0.03, h * 0.45, 0.075), (0.006, h * 0.5, 0.006), shade(color, 0.7), PLASTIC)
    return ObjectModel(standing_on_floor(b.build()))


CATEGORIES: list[Category] = [
    Category(
        name="cushion",
        shapes={"round": "round cushion", "bolster": "bolster cushion"},
        colors=(*TEXTILE_COLORS[3:], *TEXTILE_COLORS[:3]),  # shown in a colour, not white
        materials=("fabric", "leather"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.8, "bedroom": 0.3, "study": 0.05},
        build=build_cushion,
    ),
    Category(
        name="blanket",
        shapes={"folded": "folded blanket", "rolled": "rolled blanket"},
        colors=(*TEXTILE_COLORS[5:], *TEXTILE_COLORS[:5]),
        materials=("fabric",),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.5, "living room": 0.3},
        build=build_blanket,
    ),
    Category(
        name="sheet",
        shapes={"folded": "folded bed sheet", "stack": "stack of bed sheets"},
        colors=(*BEDDING_COLORS[1:], BEDDING_COLORS[0]),
        materials=("fabric",),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.3, "storage room": 0.2},
        build=build_sheet,
    ),
    Category(
        name="blinds",
        shapes={"venetian": "venetian blinds", "roller": "roller blind"},
        colors=("white", "cream", "beige", "gray", "brown", "black"),
        materials=("plastic", "wood", "fabric"),
        placement=Placement.WALL_MOUNTED,
        rooms={"bedroom": 0.3, "living room": 0.3, "kitchen": 0.3, "study": 0.3, "bathroom": 0.2},
        build=build_blinds,
        wall_height=0.95,
    ),
]
