"""Plants, curtains and fireplaces; lamps and ornaments come from :mod:`lighting` and
:mod:`ornaments`.

The curtain is wall-mounted: its back is on z = 0 and its bottom on y = 0, so the model's
origin is the bottom centre of its back, and ``wall_height`` is the height of that origin.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue import lighting, ornaments
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.parts import beam, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

FOLIAGE = material_index("foliage")
METAL = material_index("metal")
PLAIN = material_index("plain")
GLASS = material_index("glass")
POTS = (("orange", "ceramic"), ("white", "ceramic"), ("dark gray", "plastic"), ("beige", "ceramic"))


def build_plant(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pot with soil and leaves: a bush, a small tree, a snake plant or a succulent rosette."""
    s = style.scale
    leaf = color_rgb(style.color)
    pot_color, pot_mat = POTS[int(rng.integers(len(POTS)))]
    wide = style.shape == "succulent"
    r, pot_h = (0.2 if wide else 0.14) * s, (0.2 if wide else 0.3) * s
    b = MeshBuilder()
    b.cylinder(
        (0.0, 0.0, 0.0),
        r * 0.75,
        pot_h,
        color_rgb(pot_color),
        material_index(pot_mat),
        segments=10,
        radius_top=r,
    )
    b.cylinder(
        (0.0, pot_h - 0.03 * s, 0.0),
        r * 0.95,
        0.02 * s,
        color_rgb("dark brown"),
        PLAIN,
        segments=10,
    )
    top = pot_h - 0.01 * s
    if style.shape in ("spiky", "succulent"):
        n = int(rng.integers(7, 11))
        length, spread = (0.25, 0.9) if wide else (float(rng.uniform(0.55, 0.8)), 0.25)
        for k in range(n):
            a = 2 * math.pi * k / n + float(rng.uniform(-0.3, 0.3))
            lean = spread * float(rng.uniform(0.5, 1.0))
            tip = (math.cos(a) * math.sin(lean), math.cos(lean), math.sin(a) * math.sin(lean))
            base = (0.3 * r * math.cos(a), top, 0.3 * r * math.sin(a))
            end = tuple(p + t * length * s for p, t in zip(base, tip, strict=True))
            beam(
                b,
                base,
                (end[0], end[1], end[2]),
                (0.07 if wide else 0.05) * s,
                0.012 * s,
                shade(leaf, float(rng.uniform(0.85, 1.15))),
                FOLIAGE,
                side=(-math.sin(a), 0.0, math.cos(a)),
            )
        return ObjectModel(b.build())
    if style.shape == "tall":
        trunk_h = float(rng.uniform(0.7, 1.0)) * s
        b.cylinder(
            (0.0, top, 0.0),
            0.02 * s,
            trunk_h,
            color_rgb("brown"),
            material_index("wood"),
            segments=6,
        )
        centres = [(0.0, top + trunk_h + 0.1 * s, 0.0)]
        n, spread, lo, hi = 5, 0.22, trunk_h * 0.55, trunk_h + 0.1
    else:
        centres = [(0.0, top + 0.25 * s, 0.0)]
        n, spread, lo, hi = 6, r * 1.4 / s, 0.12, 0.35
    for _ in range(n):
        a = float(rng.uniform(0.0, 2 * math.pi))
        d = spread * float(rng.uniform(0.5, 1.0)) * s
        centres.append((d * math.cos(a), top + float(rng.uniform(lo, hi)) * s, d * math.sin(a)))
    for c in centres:
        size = float(rng.uniform(0.14, 0.2)) * s
        b.sphere(
            c,
            size,
            shade(leaf, float(rng.uniform(0.8, 1.2))),
            FOLIAGE,
            segments=6,
            scale=(1.0, 0.8, 1.0),
        )
    return ObjectModel(b.build())


def build_curtain(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Pleated fabric hanging from a rod: two panels drawn open, or one drawn closed."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    h = float(rng.uniform(2.1, 2.25))
    width = float(rng.uniform(1.3, 1.8)) * s
    pleat = 0.1 * s
    rod_y, rod_z = h + 0.03, 0.2 * s
    b = MeshBuilder()
    b.cylinder(
        (-width / 2 - 0.05, rod_y, rod_z),
        0.012,
        width + 0.1,
        color_rgb("silver"),
        METAL,
        segments=6,
        axis="x",
    )
    for x in (-1, 1):
        b.sphere(
            (x * (width / 2 + 0.06), rod_y, rod_z), 0.025, color_rgb("silver"), METAL, segments=6
        )
        b.box(
            (x * (width / 2 - 0.05), rod_y - 0.01, rod_z / 2),
            (0.02, 0.02, rod_z),
            color_rgb("silver"),
            METAL,
        )
    panels = (
        [(-width / 2, width / 2, 0.35)]
        if style.shape == "closed"
        else [(-width / 2, -width / 2 + 0.3 * s, 0.95), (width / 2 - 0.3 * s, width / 2, 0.95)]
    )
    for x0, x1, bunch in panels:
        n = max(2, round((x1 - x0) / pleat))
        step = (x1 - x0) / n
        fold_z = 0.5 * step * math.tan(bunch) + 0.012  # pleats clear of the wall
        for k in range(n):
            a = bunch if k % 2 == 0 else -bunch
            length = step / math.cos(bunch)
            b.box(
                (x0 + step * (k + 0.5), h / 2, fold_z),
                (length, h, 0.012),
                color,
                mat,
                yaw=a,
                faces="+z-z+y",
            )
    return ObjectModel(b.build())


def build_fireplace(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A surround with a dark firebox, logs and a flame, a hearth and a mantel shelf."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, h, d = float(rng.uniform(1.2, 1.5)) * s, 1.05 * s, 0.3 * s
    open_w, open_h, hearth = w * 0.5, h * 0.55, 0.06 * s
    black = color_rgb("black")
    b = MeshBuilder()
    b.box((0.0, hearth / 2, 0.1 * s), (w + 0.1 * s, hearth, d + 0.2 * s), shade(color, 0.8), mat)
    side = (w - open_w) / 2
    for x in (-1, 1):
        b.box(
            (x * (open_w + side) / 2, hearth + (h - hearth) / 2, 0.0),
            (side, h - hearth, d),
            color,
            mat,
        )
    lintel = h - hearth - open_h
    b.box((0.0, h - lintel / 2, 0.0), (open_w, lintel, d), color, mat)
    b.box((0.0, hearth + open_h / 2, -d / 2 + 0.02), (open_w, open_h, 0.04), black, PLAIN)
    b.box((0.0, hearth + 0.005, 0.0), (open_w, 0.01, d), shade(black, 2.0), PLAIN, faces="+y")
    if style.shape == "modern":
        b.box((0.0, hearth + open_h / 2, d / 2 - 0.01), (open_w, open_h, 0.004), black, GLASS)
    else:
        for k in range(2):
            b.cylinder(
                (-open_w * 0.3, hearth + 0.04 * s + 0.06 * s * k, -0.02 * (k - 1)),
                0.035 * s,
                open_w * 0.6,
                color_rgb("brown"),
                material_index("wood"),
                segments=6,
                axis="x",
            )
        b.sphere(
            (0.0, hearth + 0.17 * s, 0.0),
            0.1 * s,
            (1.0, 0.55, 0.1),
            PLAIN,
            segments=6,
            scale=(1.5, 0.8, 0.6),
        )
    shelf_d = d + 0.08 * s
    b.box((0.0, h + 0.03 * s, 0.04 * s), (w + 0.12 * s, 0.06 * s, shelf_d), shade(color, 0.9), mat)
    top = h + 0.06 * s
    return ObjectModel(b.build(), [Surface(top, (0.0, 0.04 * s), (w + 0.12 * s, shelf_d))])


CATEGORIES: list[Category] = [
    Category(
        name="plant",
        shapes={
            "bushy": "potted plant",
            "tall": "potted tree",
            "spiky": "snake plant",
            "succulent": "succulent",
        },
        colors=("green", "dark green"),
        materials=("foliage",),
        placement=Placement.CORNER,
        rooms={
            "living room": 1.5,
            "bedroom": 0.6,
            "kitchen": 0.5,
            "dining room": 0.8,
            "bathroom": 0.3,
            "toilet": 0.2,
            "study": 0.7,
            "corridor": 0.6,
            "gym": 0.4,
        },
        build=build_plant,
    ),
    Category(
        name="curtain",
        shapes={"open": "open curtains", "closed": "drawn curtain"},
        colors=("white", "cream", "beige", "gray", "blue", "navy", "red", "dark green", "purple"),
        materials=("fabric",),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "living room": 1.0,
            "bedroom": 1.0,
            "dining room": 0.6,
            "study": 0.5,
            "kitchen": 0.2,
            "bathroom": 0.1,
            "gym": 0.2,
        },
        build=build_curtain,
        wall_height=0.1,
    ),
    Category(
        name="fireplace",
        shapes={"classic": "fireplace", "modern": "modern fireplace"},
        colors=("white", "beige", "gray", "brown", "dark brown", "black", "cream"),
        materials=("marble", "wood", "tile", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"living room": 0.25},
        build=build_fireplace,
    ),
    *lighting.CATEGORIES,
    *ornaments.CATEGORIES,
]
