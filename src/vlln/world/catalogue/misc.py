"""Radiators, coat racks, and the instrument, fitness and container categories.

The radiator is wall-mounted: its back is on z = 0 and its bottom on y = 0, so the model's
origin is the bottom centre of its back, and ``wall_height`` is the height of that origin.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue import containers, fitness, instruments
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

METAL = material_index("metal")
COAT_COLORS = ("black", "navy", "beige", "gray", "brown", "red", "dark green")


def build_radiator(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Vertical columns joined by pipes with a valve (column), or a flat ribbed panel."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, h = float(rng.uniform(0.6, 1.2)) * s, 0.6 * s
    gap, depth = 0.03, 0.07
    b = MeshBuilder()
    for x in (-w * 0.35, w * 0.35):
        b.box((x, h * 0.7, gap / 2), (0.03, 0.03, gap), color_rgb("gray"), METAL)
    if style.shape == "panel":
        b.box((0.0, h / 2, gap + depth / 4), (w, h, depth / 2), color, mat)
        for k in range(1, 8):
            b.box(
                (0.0, h * k / 8, gap + depth / 2 + 0.002),
                (w - 0.01, 0.008, 0.004),
                shade(color, 0.8),
                mat,
                faces="+z+y",
            )
        b.box(
            (0.0, h + 0.001, gap + depth / 4),
            (w - 0.02, 0.0, depth / 2 - 0.01),
            shade(color, 0.3),
            mat,
            faces="+y",
        )
    else:
        n = max(6, round(w / 0.065))
        pitch = w / n
        for k in range(n):
            x = -w / 2 + pitch * (k + 0.5)
            b.box(
                (x, h / 2, gap + depth / 2), (pitch * 0.7, h, depth), color, mat, faces="+z+x-x+y"
            )
        for y in (0.06 * s, h - 0.06 * s):
            b.cylinder((-w / 2, y, gap + depth / 2), 0.018, w, color, mat, segments=6, axis="x")
    b.cylinder(
        (w / 2, 0.04 * s, gap + depth / 2),
        0.012,
        0.06 * s,
        color_rgb("silver"),
        METAL,
        segments=6,
        axis="x",
    )
    b.cylinder(
        (w / 2 + 0.06 * s, 0.0, gap + depth / 2),
        0.02,
        0.08 * s,
        color_rgb("white"),
        material_index("plastic"),
        segments=8,
    )
    return ObjectModel(b.build())


def build_coat_rack(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pole on three feet with hooks at the top, sometimes with a coat hanging from one."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    h = float(rng.uniform(1.7, 1.85)) * s
    b = MeshBuilder()
    for k in range(3):
        a = 2 * math.pi * k / 3
        foot = (0.25 * s * math.cos(a), 0.02 * s, 0.25 * s * math.sin(a))
        beam(b, foot, (0.0, 0.25 * s, 0.0), 0.035 * s, 0.035 * s, color, mat)
    b.cylinder((0.0, 0.0, 0.0), 0.02 * s, h, color, mat, segments=8)
    b.sphere((0.0, h + 0.03 * s, 0.0), 0.04 * s, color, mat, segments=8)
    hooks = []
    for k in range(6):
        a = 2 * math.pi * k / 6
        y = h - (0.04 if k % 2 else 0.14) * s
        tip = (0.14 * s * math.cos(a), y + 0.08 * s, 0.14 * s * math.sin(a))
        beam(b, (0.0, y, 0.0), tip, 0.02 * s, 0.02 * s, color, mat)
        hooks.append(tip)
    behind = [k for k, (x, _, z) in enumerate(hooks) if z < 0.0]  # coats hang at the back
    for k in rng.choice(behind, min(len(behind), int(rng.integers(0, 3))), replace=False):
        x, y, z = hooks[int(k)]
        coat = color_rgb(COAT_COLORS[int(rng.integers(len(COAT_COLORS)))])
        out = np.array([x, 0.0, z]) / math.hypot(x, z)
        side = (-out[2], 0.0, out[0])
        collar = (x + out[0] * 0.06, y - 0.03 * s, z + out[2] * 0.06)
        chest = (x + out[0] * 0.12, y - 0.25 * s, z + out[2] * 0.12)
        hem = (x + out[0] * 0.14, y - 0.9 * s, z + out[2] * 0.14)
        fabric = material_index("fabric")
        beam(b, collar, chest, 0.26 * s, 0.1 * s, coat, fabric, side=side)
        beam(b, chest, hem, 0.4 * s, 0.13 * s, coat, fabric, side=side)
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="heater",
        shapes={"column": "column radiator", "panel": "panel radiator"},
        colors=("white", "cream", "gray", "silver", "black"),
        materials=("metal",),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "living room": 0.8,
            "bedroom": 0.8,
            "bathroom": 0.5,
            "kitchen": 0.4,
            "study": 0.6,
            "corridor": 0.4,
            "dining room": 0.5,
            "toilet": 0.2,
        },
        build=build_radiator,
        wall_height=0.12,
    ),
    Category(
        name="coat rack",
        shapes={"standing": "coat stand"},
        colors=("brown", "dark brown", "black", "white", "silver"),
        materials=("wood", "metal"),
        placement=Placement.CORNER,
        rooms={"corridor": 0.5, "bedroom": 0.1, "living room": 0.05},
        build=build_coat_rack,
    ),
    *instruments.CATEGORIES,
    *fitness.CATEGORIES,
    *containers.CATEGORIES,
]
