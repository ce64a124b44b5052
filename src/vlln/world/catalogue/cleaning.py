"""Cleaning and paper things: detergent, sponges, brushes, tissue boxes and tissue rolls.

Every model stands on a counter, a shelf or a table and fits a 0.4 x 0.3 m footprint at the
largest scale.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

PLAIN = material_index("plain")
PLASTIC = material_index("plastic")
WOOD = material_index("wood")
WHITE = color_rgb("white")
BRISTLE = color_rgb("beige")


def build_detergent(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A laundry jug with a handle and a cap, a spray bottle with a trigger, or a powder box."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    label = WHITE if style.color != "white" else color_rgb("blue")
    b = MeshBuilder()
    if style.shape == "box":
        w, h, d = 0.2 * s, 0.25 * s, 0.08 * s
        b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
        b.box((0.0, h * 0.55, d / 2 + 0.001), (w * 0.7, h * 0.35, 0.002), label, PLAIN)
        b.box((0.0, h + 0.01 * s, -d * 0.2), (w * 0.4, 0.02 * s, 0.012 * s), shade(color, 0.7), mat)
        return ObjectModel(b.build())
    if style.shape == "spray":
        h, r = float(rng.uniform(0.17, 0.2)) * s, 0.038 * s
        b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=10)
        b.cylinder((0.0, h * 0.3, 0.0), r + 0.001, h * 0.4, label, PLAIN, segments=10, caps=False)
        head = color_rgb("white" if style.color != "white" else "green")
        b.cylinder((0.0, h, 0.0), 0.016 * s, 0.02 * s, head, PLASTIC, segments=6)
        b.box((0.0, h + 0.04 * s, 0.02 * s), (0.028 * s, 0.04 * s, 0.075 * s), head, PLASTIC)
        beam(
            b,
            (0.0, h + 0.02 * s, 0.035 * s),
            (0.0, h - 0.03 * s, 0.05 * s),
            0.015 * s,
            0.01 * s,
            head,
            PLASTIC,
        )
        return ObjectModel(b.build())
    w, h, d = 0.16 * s, float(rng.uniform(0.22, 0.26)) * s, 0.1 * s
    b.box((0.0, h * 0.45, 0.0), (w, h * 0.9, d), color, mat)
    b.cylinder((w * 0.25, h * 0.9, 0.0), 0.025 * s, 0.03 * s, shade(color, 0.6), mat, segments=8)
    ring(
        b,
        (-w * 0.2, h * 0.9, 0.0),
        0.045 * s,
        0.014 * s,
        0.03 * s,
        color,
        mat,
        segments=8,
        arc=(0.0, math.pi),
    )
    b.box((0.0, h * 0.45, d / 2 + 0.001), (w * 0.75, h * 0.4, 0.002), label, PLAIN)
    return ObjectModel(b.build())


def build_sponge(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A kitchen sponge with a green scouring layer, or a soft rounded bath sponge."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    w, d = float(rng.uniform(0.09, 0.11)) * s, 0.07 * s
    if style.shape == "bath":
        b.sphere(
            (0.0, 0.035 * s, 0.0),
            1.0,
            color,
            mat,
            segments=10,
            scale=(w * 0.7, 0.035 * s, d * 0.75),
        )
        return ObjectModel(b.build())
    scour = color_rgb("dark green" if style.color != "dark green" else "black")
    b.box((0.0, 0.004 * s, 0.0), (w, 0.008 * s, d), scour, mat)
    b.box((0.0, 0.008 * s + 0.0125 * s, 0.0), (w, 0.025 * s, d), color, mat)
    return ObjectModel(b.build())


def _bristles(
    b: MeshBuilder, x0: float, x1: float, z_half: float, y: float, height: float, rows: int
) -> None:
    """Rows of bristle tufts hanging down from ``y`` under a brush head."""
    for i in range(rows):
        for j in range(2):
            x = x0 + (x1 - x0) * (i + 0.5) / rows
            z = z_half * (j - 0.5)
            b.box((x, y - height / 2, z), (0.006, height, 0.006), BRISTLE, PLAIN)


def build_brush(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A paddle hairbrush, a dish brush with a long handle, or a scrubbing brush block."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "scrubbing":
        w, d, t = 0.14 * s, 0.06 * s, 0.025 * s
        b.box((0.0, 0.018 * s + t / 2, 0.0), (w, t, d), color, mat)
        b.box((0.0, 0.009 * s, 0.0), (w * 0.92, 0.018 * s, d * 0.85), BRISTLE, PLAIN)
        b.box((0.0, 0.018 * s + t, 0.0), (w * 0.5, 0.01 * s, d * 0.4), shade(color, 0.7), mat)
        return ObjectModel(b.build())
    if style.shape == "dish":
        r = 0.028 * s
        b.cylinder((0.0, 0.0, 0.0), r * 0.9, 0.025 * s, BRISTLE, PLAIN, segments=8, axis="x")
        b.cylinder((0.025 * s, 0.0, 0.0), r, 0.012 * s, color, mat, segments=8, axis="x")
        beam(b, (0.035 * s, 0.0, 0.0), (0.24 * s, 0.012 * s, 0.0), 0.022 * s, 0.014 * s, color, mat)
        model = b.build()
        lifted = model.transformed(0.0, (0.0, r, 0.0))
        return ObjectModel(lifted)
    length = float(rng.uniform(0.22, 0.25)) * s
    head_r, t = 0.04 * s, 0.012 * s
    y = 0.022 * s
    b.sphere(
        (0.0, y + t / 2, 0.0), 1.0, color, mat, segments=10, scale=(head_r * 1.3, t / 2, head_r)
    )
    _bristles(b, -head_r, head_r, head_r, y, y, rows=5)
    b.box((-head_r * 0.9 - 0.006, y / 2, 0.0), (0.006, y, head_r * 0.9), BRISTLE, PLAIN)
    beam(b, (head_r * 1.2, y + t / 2, 0.0), (length - head_r, y + t, 0.0), 0.025 * s, t, color, mat)
    return ObjectModel(b.build())


def build_tissue_box(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A box of tissues with the top one pulled up through the slot."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    square = style.shape == "square"
    w, h, d = (0.12 if square else 0.24) * s, (0.13 if square else 0.09) * s, 0.12 * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    b.box(
        (0.0, h + 0.0005, 0.0),
        (w * 0.55 if not square else w * 0.4, 0.001, 0.02 * s),
        shade(color, 0.4),
        mat,
        faces="+y",
    )
    fold = float(rng.uniform(-0.3, 0.3))
    tip = (0.015 * s * math.sin(fold), h + 0.06 * s, 0.015 * s * math.cos(fold))
    beam(b, (0.0, h, 0.0), tip, 0.07 * s, 0.002, WHITE, PLAIN)
    beam(b, tip, (tip[0], tip[1] + 0.02 * s, tip[2] - 0.02 * s), 0.06 * s, 0.002, WHITE, PLAIN)
    return ObjectModel(b.build())


def build_tissue(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A kitchen roll on its stand, or a soft pack of tissues with one poking out."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "roll":
        h, r = 0.24 * s, float(rng.uniform(0.05, 0.06)) * s
        stand = color_rgb("silver")
        b.cylinder(
            (0.0, 0.0, 0.0), r * 1.15, 0.012 * s, stand, material_index("metal"), segments=10
        )
        b.cylinder((0.0, 0.012 * s, 0.0), r, h, color, mat, segments=12)
        b.cylinder(
            (0.0, 0.012 * s + h, 0.0), 0.02 * s, 0.001, color_rgb("beige"), PLAIN, segments=8
        )
        b.cylinder(
            (0.0, 0.012 * s + h, 0.0),
            0.006 * s,
            0.03 * s,
            stand,
            material_index("metal"),
            segments=6,
        )
        b.box(
            (r * 0.7, 0.012 * s + h * 0.3, r * 0.7),
            (0.002, h * 0.55, 0.06 * s),
            color,
            mat,
            yaw=math.pi / 4,
        )
        return ObjectModel(b.build())
    w, h, d = 0.11 * s, 0.03 * s, 0.055 * s
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    b.sphere(
        (0.0, h, 0.0),
        1.0,
        color,
        mat,
        segments=8,
        scale=(w * 0.45, 0.008 * s, d * 0.45),
        upper_half_only=True,
    )
    beam(
        b,
        (0.0, h, 0.0),
        (0.01 * s, h + 0.025 * s, 0.0),
        0.04 * s,
        0.002,
        WHITE,
        PLAIN,
        side=(0.0, 0.0, 1.0),
    )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="detergent",
        shapes={"bottle": "detergent bottle", "spray": "spray bottle", "box": "detergent box"},
        colors=("blue", "orange", "green", "white", "purple", "red", "yellow", "light blue"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"storage room": 0.4, "kitchen": 0.2, "bathroom": 0.15},
        build=build_detergent,
    ),
    Category(
        name="sponge",
        shapes={"kitchen": "kitchen sponge", "bath": "bath sponge"},
        colors=("yellow", "green", "blue", "pink", "orange", "beige"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.4, "bathroom": 0.15},
        build=build_sponge,
    ),
    Category(
        name="brush",
        shapes={"hair": "hair brush", "dish": "dish brush", "scrubbing": "scrubbing brush"},
        colors=("black", "brown", "white", "pink", "blue", "red", "green"),
        materials=("plastic", "wood"),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.25, "bedroom": 0.1, "kitchen": 0.2, "storage room": 0.1},
        build=build_brush,
    ),
    Category(
        name="tissue box",
        shapes={"rectangular": "rectangular tissue box", "square": "square tissue box"},
        colors=("white", "blue", "pink", "green", "beige", "brown", "gray", "light blue"),
        materials=("plain", "wood", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.3, "bedroom": 0.2, "bathroom": 0.2, "study": 0.1},
        build=build_tissue_box,
    ),
    Category(
        name="tissue",
        shapes={"roll": "kitchen roll", "pack": "pack of tissues"},
        colors=("white", "cream", "light blue", "pink"),
        materials=("plain",),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.3, "toilet": 0.1, "bedroom": 0.05},
        build=build_tissue,
    ),
]
