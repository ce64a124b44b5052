"""Things that hold other things and stand on the floor: bins, bags, baskets, boxes, stands."""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

BAG_COLORS = ("black", "navy", "red", "gray", "blue", "green", "purple", "orange")
BLACK = color_rgb("black")
PLASTIC = material_index("plastic")
METAL = material_index("metal")


def _open_top(b: MeshBuilder, r0: float, r1: float, h: float, color: Rgb, mat: int) -> None:
    """An open round container: a wall, a rolled rim and a shadowed inside."""
    b.cylinder((0.0, 0.0, 0.0), r0, h, color, mat, segments=12, radius_top=r1, caps=False)
    ring(
        b,
        (0.0, h - 0.006, 0.0),
        r1 + 0.008,
        0.014,
        0.012,
        shade(color, 0.8),
        mat,
        axis="y",
        segments=12,
    )
    b.cylinder(
        (0.0, h * 0.85, 0.0), r0 + (r1 - r0) * 0.85, 0.002, shade(color, 0.35), mat, segments=12
    )


def build_trash_can(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pedal bin with a domed lid, a swing-top bin, or an open wastebasket."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    lid = shade(color, 0.8)
    b = MeshBuilder()
    if style.shape == "swing-top":
        w, h = 0.3 * s, (0.62 + float(rng.uniform(0.0, 0.1))) * s
        b.box((0.0, h / 2, 0.0), (w, h, w), color, mat)
        b.box((0.0, h + 0.03 * s, 0.0), (w * 1.02, 0.06 * s, w * 1.02), lid, mat)
        b.box(
            (0.0, h + 0.03 * s, w * 0.51 + 0.001),
            (w * 0.6, 0.03 * s, 0.0),
            BLACK,
            PLASTIC,
            faces="+z",
        )
    elif style.shape == "pedal":
        r, h = 0.14 * s, (0.42 + float(rng.uniform(0.0, 0.08))) * s
        b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=12)
        b.sphere(
            (0.0, h, 0.0),
            r * 1.02,
            lid,
            mat,
            segments=12,
            scale=(1.0, 0.25, 1.0),
            upper_half_only=True,
        )
        b.box((0.0, 0.03 * s, r + 0.03 * s), (0.12 * s, 0.02 * s, 0.07 * s), BLACK, PLASTIC)
    else:
        _open_top(b, 0.13 * s, 0.155 * s, (0.33 + float(rng.uniform(0.0, 0.05))) * s, color, mat)
    return ObjectModel(b.build())


def build_suitcase(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An upright case on wheels with a pull handle; hard shells are ribbed, soft ones pocketed."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.44 * s, 0.25 * s
    h = float(rng.uniform(0.55, 0.7)) * s
    lift = 0.05 * s
    b = MeshBuilder()
    b.box((0.0, lift + h / 2, 0.0), (w, h, d), color, mat)
    b.box(
        (0.0, lift + h / 2, 0.0),
        (w + 0.004, h + 0.004, 0.012),
        shade(color, 0.5),
        mat,
        faces="+x-x+y",
    )
    if style.shape == "hard-shell":
        for x in (-0.25, 0.0, 0.25):
            b.box((x * w, lift + h / 2, d / 2 + 0.005), (0.03 * s, h * 0.85, 0.01), color, mat)
    else:
        b.box(
            (0.0, lift + h * 0.35, d / 2 + 0.025 * s),
            (w * 0.8, h * 0.5, 0.05 * s),
            shade(color, 0.9),
            mat,
        )
    for x in (-1, 1):
        for z in (-1, 1):
            b.cylinder(
                (x * w / 2 - 0.015 * x, 0.025 * s, z * (d / 2 - 0.03 * s) - 0.01),
                0.025 * s,
                0.02,
                BLACK,
                PLASTIC,
                segments=8,
                axis="z",
            )
        b.box(
            (x * 0.12 * s, lift + h + 0.1 * s, -d / 2 + 0.02),
            (0.015, 0.2 * s, 0.015),
            color_rgb("silver"),
            METAL,
        )
    b.box((0.0, lift + h + 0.2 * s, -d / 2 + 0.02), (0.26 * s, 0.025, 0.025), BLACK, PLASTIC)
    b.box((0.0, lift + h + 0.015, 0.0), (0.14 * s, 0.03, 0.03), BLACK, PLASTIC)
    return ObjectModel(b.build())


def build_basket(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall open storage basket with hand holes, or a low wicker basket with a handle."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "storage":
        h = float(rng.uniform(0.45, 0.6)) * s
        _open_top(b, 0.17 * s, 0.21 * s, h, color, mat)
        for x in (-1, 1):
            b.box(
                (x * 0.205 * s, h - 0.07 * s, 0.0),
                (0.02, 0.04 * s, 0.1 * s),
                shade(color, 0.3),
                mat,
                faces="+x-x",
            )
        return ObjectModel(b.build())
    r, h = 0.18 * s, float(rng.uniform(0.18, 0.24)) * s
    _open_top(b, r * 0.85, r, h, color, mat)
    ring(
        b,
        (0.0, h, 0.0),
        r * 0.95,
        0.02 * s,
        0.03 * s,
        shade(color, 0.85),
        mat,
        segments=8,
        arc=(0.0, math.pi),
    )
    return ObjectModel(b.build())


def build_box(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A cardboard box, taped shut or with its four flaps folded open."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, h = (float(v) * s for v in rng.uniform((0.35, 0.28, 0.25), (0.6, 0.45, 0.5)))
    b = MeshBuilder()
    if style.shape == "open":
        b.box((0.0, h / 2, 0.0), (w, h, d), color, mat, faces="+x-x+z-z-y")
        b.box((0.0, h * 0.6, 0.0), (w - 0.01, 0.002, d - 0.01), shade(color, 0.4), mat, faces="+y")
        for x, z, fw, reach in (
            (0, 1, w, d * 0.45),
            (0, -1, w, d * 0.45),
            (1, 0, d, d * 0.45),
            (-1, 0, d, d * 0.45),
        ):
            edge = (x * w / 2, h, z * d / 2)
            tip = (edge[0] + x * reach * 0.7, h + reach * 0.7, edge[2] + z * reach * 0.7)
            beam(
                b,
                edge,
                tip,
                fw,
                0.004,
                shade(color, 0.95),
                mat,
                side=(1.0, 0.0, 0.0) if x == 0 else (0.0, 0.0, 1.0),
            )
        return ObjectModel(b.build())
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    tape = shade(color_rgb("beige"), 1.05)
    b.box((0.0, h + 0.001, 0.0), (0.06 * s, 0.002, d + 0.002), tape, PLASTIC, faces="+y+z-z")
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_backpack(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A rounded pack with a front pocket, shoulder straps on the back and a top loop."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.3 * s, 0.16 * s
    h = float(rng.uniform(0.34, 0.42)) * s
    dark = shade(color, 0.6)
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    b.sphere(
        (0.0, h, 0.0), w / 2, color, mat, segments=8, scale=(1.0, 0.5, d / w), upper_half_only=True
    )
    b.box((0.0, h * 0.3, d / 2 + 0.03 * s), (w * 0.75, h * 0.42, 0.06 * s), dark, mat)
    b.box((0.0, h * 0.52, d / 2 + 0.061 * s), (w * 0.7, 0.01, 0.003), BLACK, PLASTIC)
    for x in (-1, 1):
        beam(
            b,
            (x * 0.07 * s, h * 1.05, -d / 2),
            (x * 0.09 * s, h * 0.12, -d / 2 - 0.01),
            0.05 * s,
            0.02,
            dark,
            mat,
            side=(1.0, 0.0, 0.0),
        )
    ring(
        b,
        (0.0, h + w * 0.25, 0.0),
        0.04 * s,
        0.012,
        0.02,
        dark,
        mat,
        segments=6,
        arc=(0.0, math.pi),
    )
    return ObjectModel(b.build())


def build_umbrella_stand(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An open cylinder holding two or three folded umbrellas with hooked handles."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    r, h = 0.11 * s, float(rng.uniform(0.45, 0.55)) * s
    b = MeshBuilder()
    _open_top(b, r, r, h, color, mat)
    for k in range(int(rng.integers(2, 4))):
        lean = (k - 1) * 0.08 * s + float(rng.uniform(-0.02, 0.02))
        z = float(rng.uniform(-0.04, 0.04)) * s
        canopy = color_rgb(BAG_COLORS[int(rng.integers(len(BAG_COLORS)))])
        low, mid = (lean * 0.3, h * 0.6, z), (lean, h + 0.25 * s, z)
        top = (lean * 1.2, h + 0.4 * s, z)
        beam(b, low, mid, 0.045 * s, 0.045 * s, canopy, material_index("fabric"))
        beam(b, mid, top, 0.012, 0.012, color_rgb("silver"), METAL)
        ring(
            b,
            (top[0] + 0.03 * s, top[1], z),
            0.035 * s,
            0.012,
            0.015,
            BLACK,
            PLASTIC,
            segments=5,
            arc=(0.0, math.pi),
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="garbage",
        shapes={"pedal": "pedal bin", "swing-top": "swing-top bin", "open": "wastebasket"},
        colors=("silver", "white", "black", "gray", "blue", "green"),
        materials=("metal", "plastic"),
        placement=Placement.CORNER,
        rooms={
            "kitchen": 1.0,
            "bathroom": 0.7,
            "toilet": 0.6,
            "study": 0.6,
            "bedroom": 0.35,
            "living room": 0.3,
            "dining room": 0.2,
            "corridor": 0.15,
            "gym": 0.4,
            "storage room": 0.2,
        },
        build=build_trash_can,
    ),
    Category(
        name="luggage",
        shapes={"hard-shell": "hard-shell suitcase", "soft": "soft suitcase"},
        colors=BAG_COLORS,
        materials=("plastic", "fabric", "leather"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.3, "storage room": 0.6, "corridor": 0.2},
        build=build_suitcase,
    ),
    Category(
        name="basket",
        shapes={"storage": "storage basket", "wicker": "wicker basket"},
        colors=("beige", "brown", "white", "gray", "dark brown"),
        materials=("wood", "fabric", "plastic"),
        placement=Placement.CORNER,
        rooms={
            "bathroom": 0.4,
            "bedroom": 0.3,
            "storage room": 0.4,
            "living room": 0.15,
            "kitchen": 0.1,
        },
        build=build_basket,
    ),
    Category(
        name="box",
        shapes={"closed": "cardboard box", "open": "open cardboard box"},
        colors=("brown", "beige", "white"),
        materials=("plain",),
        placement=Placement.AGAINST_WALL,
        rooms={
            "storage room": 2.0,
            "corridor": 0.15,
            "study": 0.15,
            "bedroom": 0.15,
            "gym": 0.1,
            "living room": 0.05,
        },
        build=build_box,
    ),
    Category(
        name="backpack",
        shapes={"daypack": "backpack"},
        colors=BAG_COLORS,
        materials=("fabric", "leather"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.35, "study": 0.2, "corridor": 0.2, "living room": 0.1, "gym": 0.15},
        build=build_backpack,
    ),
    Category(
        name="umbrella stand",
        shapes={"round": "umbrella stand"},
        colors=("black", "gray", "silver", "white", "brown", "red"),
        materials=("metal", "ceramic", "plastic"),
        placement=Placement.CORNER,
        rooms={"corridor": 0.3},
        build=build_umbrella_stand,
    ),
]
