"""Bathroom things: soap, its dish and dispenser, shampoo, cosmetics, a hair dryer, a loofah.

All stand on the basin, a shelf or a cabinet top except the body loofah, which hangs from a
hook on the wall with its back on z = 0 (the model's origin is the bottom centre of its back).
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

SOFT_COLORS = ("white", "pink", "cream", "light blue", "green", "yellow", "purple", "beige")
BATH_COLORS = ("white", "blue", "light blue", "green", "pink", "purple", "orange", "black")
PLAIN = material_index("plain")
PLASTIC = material_index("plastic")
METAL = material_index("metal")
WHITE = color_rgb("white")
SILVER = color_rgb("silver")


def _soap_bar(b: MeshBuilder, y: float, size: float, color: Rgb, mat: int) -> None:
    """A bar of soap with a softened, slightly smaller top."""
    w, h, d = 0.085 * size, 0.022 * size, 0.055 * size
    b.box((0.0, y + h / 2, 0.0), (w, h, d), color, mat)
    b.box((0.0, y + h + 0.004 * size, 0.0), (w * 0.88, 0.008 * size, d * 0.82), color, mat)


def build_soap(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A bar of soap, bare or in a paper band with a printed label."""
    s = style.scale * float(rng.uniform(0.95, 1.1))
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    _soap_bar(b, 0.0, s, color, mat)
    if style.shape == "wrapped":
        band = color_rgb("navy" if style.color != "navy" else "gold")
        b.box((0.0, 0.0135 * s, 0.0), (0.03 * s, 0.027 * s, 0.058 * s), band, PLAIN)
    return ObjectModel(b.build())


def _pump(b: MeshBuilder, x: float, top: float, s: float, color: Rgb) -> None:
    """A pump head with a spout towards +z on a body whose top is at ``top``."""
    b.cylinder((x, top, 0.0), 0.012 * s, 0.025 * s, color, PLASTIC, segments=6)
    b.cylinder((x, top + 0.025 * s, 0.0), 0.016 * s, 0.015 * s, color, PLASTIC, segments=6)
    beam(
        b,
        (x, top + 0.033 * s, 0.0),
        (x, top + 0.03 * s, 0.045 * s),
        0.01 * s,
        0.01 * s,
        color,
        PLASTIC,
    )


def build_soap_dispenser(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pump bottle: a round one, or a square one with a silver pump."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    h = float(rng.uniform(0.12, 0.15)) * s
    b = MeshBuilder()
    if style.shape == "square":
        b.box((0.0, h / 2, 0.0), (0.07 * s, h, 0.07 * s), color, mat)
        _pump(b, 0.0, h, s, SILVER)
    else:
        b.cylinder((0.0, 0.0, 0.0), 0.035 * s, h, color, mat, segments=10)
        b.cylinder(
            (0.0, h, 0.0), 0.035 * s, 0.015 * s, color, mat, segments=10, radius_top=0.015 * s
        )
        _pump(b, 0.0, h + 0.015 * s, s, shade(color, 0.6))
    return ObjectModel(b.build())


def build_soap_dish(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A shallow dish, round or rectangular, with a bar of soap in it."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    h = 0.022 * s
    if style.shape == "round":
        b.cylinder((0.0, 0.0, 0.0), 0.05 * s, h, color, mat, segments=12, radius_top=0.065 * s)
    else:
        w, d, wall = 0.13 * s, 0.09 * s, 0.008 * s
        b.box((0.0, wall / 2, 0.0), (w, wall, d), color, mat)
        for x in (-1, 1):
            b.box((x * (w - wall) / 2, h / 2, 0.0), (wall, h, d), color, mat)
        for z in (-1, 1):
            b.box((0.0, h / 2, z * (d - wall) / 2), (w - 2 * wall, h, wall), color, mat)
    soap = color_rgb(("pink", "cream", "light blue", "green")[int(rng.integers(4))])
    _soap_bar(b, 0.006 * s, 0.85 * s, soap, PLAIN)
    return ObjectModel(b.build())


def build_shampoo(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A flat bottle standing upside down on its flip cap, or an upright bottle with a pump."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    h = float(rng.uniform(0.17, 0.21)) * s
    label = color_rgb("white" if style.color != "white" else "blue")
    b = MeshBuilder()
    if style.shape == "pump":
        b.cylinder((0.0, 0.0, 0.0), 0.04 * s, h, color, mat, segments=10)
        b.cylinder((0.0, h * 0.3, 0.0), 0.0405 * s, h * 0.4, label, PLAIN, segments=10, caps=False)
        _pump(b, 0.0, h, s, WHITE)
        return ObjectModel(b.build())
    cap, w, d = 0.03 * s, 0.075 * s, 0.04 * s
    b.box((0.0, cap / 2, 0.0), (w * 0.55, cap, d * 0.8), shade(color, 0.6), PLASTIC)
    b.box((0.0, cap + h * 0.4, 0.0), (w, h * 0.8, d), color, mat)
    b.sphere(
        (0.0, cap + h * 0.8, 0.0), 1.0, color, mat, segments=10, scale=(w / 2, h * 0.12, d / 2)
    )
    b.box((0.0, cap + h * 0.45, d / 2 + 0.001), (w * 0.75, h * 0.35, 0.002), label, PLAIN)
    return ObjectModel(b.build())


def build_cosmetics(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A perfume bottle, a row of lipsticks, or a make-up palette with a brush."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    gold = color_rgb("gold")
    b = MeshBuilder()
    if style.shape == "perfume":
        h = float(rng.uniform(0.08, 0.1)) * s
        b.box((0.0, h / 2, 0.0), (0.07 * s, h, 0.035 * s), color, mat)
        b.cylinder((0.0, h, 0.0), 0.008 * s, 0.012 * s, gold, METAL, segments=6)
        b.box((0.0, h + 0.025 * s, 0.0), (0.03 * s, 0.028 * s, 0.03 * s), gold, METAL)
        return ObjectModel(b.build())
    if style.shape == "lipstick":
        shades = ("red", "pink", "purple", "orange")
        for k in range(3):
            x = (k - 1) * 0.03 * s
            b.cylinder((x, 0.0, 0.0), 0.011 * s, 0.05 * s, color, mat, segments=8)
            b.cylinder((x, 0.05 * s, 0.0), 0.009 * s, 0.012 * s, gold, METAL, segments=8)
            tint = color_rgb(shades[int(rng.integers(len(shades)))])
            b.cylinder(
                (x, 0.062 * s, 0.0),
                0.007 * s,
                0.014 * s,
                tint,
                PLAIN,
                segments=6,
                radius_top=0.003 * s,
            )
        return ObjectModel(b.build())
    w, d, t = 0.14 * s, 0.09 * s, 0.012 * s
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    powders = ("pink", "beige", "brown", "purple", "gold", "red")
    for k in range(6):
        x, z = (k % 3 - 1) * w * 0.3, (k // 3 - 0.5) * d * 0.45
        tint = color_rgb(powders[(k + int(rng.integers(6))) % 6])
        b.cylinder((x, t, z), 0.016 * s, 0.002 * s, tint, PLAIN, segments=8)
    beam(
        b,
        (-w * 0.45, t + 0.006 * s, d * 0.6),
        (w * 0.45, t + 0.006 * s, d * 0.7),
        0.008 * s,
        0.008 * s,
        color_rgb("black"),
        PLASTIC,
    )
    return ObjectModel(b.build())


def build_hair_dryer(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A hair dryer standing on its handle: a barrel with a nozzle in front and a grille behind."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    pro = style.shape == "professional"
    length, r = (0.24 if pro else 0.17) * s, (0.042 if pro else 0.036) * s
    grip = float(rng.uniform(0.13, 0.16)) * s
    b = MeshBuilder()
    b.cylinder((0.0, 0.0, 0.0), 0.025 * s, 0.012 * s, shade(color, 0.8), mat, segments=8)
    beam(b, (0.0, 0.0, 0.0), (0.0, grip, -0.02 * s), 0.035 * s, 0.03 * s, color, mat)
    y = grip + r * 0.7
    back = -length * 0.35
    b.cylinder((0.0, y, back), r, length * 0.75, color, mat, segments=10, axis="z")
    b.cylinder(
        (0.0, y, back + length * 0.75),
        r * 0.9,
        length * 0.25,
        shade(color, 0.7),
        mat,
        segments=10,
        radius_top=r * 0.6,
        axis="z",
    )
    b.cylinder(
        (0.0, y, back - 0.004 * s),
        r * 0.8,
        0.004 * s,
        color_rgb("dark gray"),
        PLASTIC,
        segments=10,
        axis="z",
    )
    switch = WHITE if style.color != "white" else SILVER
    b.box((0.0, grip * 0.7, 0.0), (0.012 * s, 0.02 * s, 0.012 * s), switch, PLASTIC)
    return ObjectModel(standing_on_floor(b.build()))


def build_body_loofah(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A ruffled bath puff, or a long loofah sponge, hanging by a cord from a wall hook."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    top = 0.24 * s
    b.box((0.0, top, 0.01 * s), (0.02 * s, 0.03 * s, 0.02 * s), SILVER, METAL)
    ring(
        b,
        (0.0, top - 0.06 * s, 0.025 * s),
        0.04 * s,
        0.004 * s,
        0.004 * s,
        shade(color, 0.7),
        PLAIN,
        axis="z",
        segments=8,
        arc=(0.0, math.pi),
    )
    if style.shape == "sponge":
        b.cylinder((0.0, 0.0, 0.034 * s), 0.03 * s, top - 0.07 * s, color, mat, segments=8)
        for k in range(5):
            b.cylinder(
                (0.0, 0.02 * s + k * 0.032 * s, 0.034 * s),
                0.033 * s,
                0.006 * s,
                shade(color, 0.8),
                mat,
                segments=8,
                caps=False,
            )
        return ObjectModel(b.build())
    r = 0.065 * s
    center = (0.0, r, r)
    b.sphere(center, r * 0.85, color, mat, segments=10)
    for k in range(8):
        a, e = 2 * math.pi * k / 8 + float(rng.uniform(-0.3, 0.3)), (k % 2 - 0.5) * 0.9
        offset = (math.cos(a) * math.cos(e), math.sin(e), math.sin(a) * math.cos(e))
        ruffle = tuple(c + o * r * 0.45 for c, o in zip(center, offset, strict=True))
        b.sphere(
            (ruffle[0], max(ruffle[1], r * 0.5), max(ruffle[2], r * 0.55)),
            r * 0.5,
            shade(color, 0.9 + 0.04 * (k % 3)),
            mat,
            segments=6,
        )
    return ObjectModel(standing_on_floor(b.build()))


CATEGORIES: list[Category] = [
    Category(
        name="soap",
        shapes={"bar": "bar of soap", "wrapped": "wrapped bar of soap"},
        colors=SOFT_COLORS,
        materials=("plain",),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.3, "toilet": 0.2, "kitchen": 0.05},
        build=build_soap,
    ),
    Category(
        name="soap dispenser",
        shapes={"round": "round soap dispenser", "square": "square soap dispenser"},
        colors=BATH_COLORS,
        materials=("plastic", "glass", "ceramic"),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.4, "toilet": 0.3, "kitchen": 0.3},
        build=build_soap_dispenser,
    ),
    Category(
        name="soap dish",
        shapes={"round": "round soap dish", "rectangular": "rectangular soap dish"},
        colors=("white", "cream", "light blue", "green", "silver", "black", "brown"),
        materials=("ceramic", "plastic", "metal", "wood"),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.3, "toilet": 0.15},
        build=build_soap_dish,
    ),
    Category(
        name="shampoo",
        shapes={"bottle": "shampoo bottle", "pump": "shampoo pump bottle"},
        colors=BATH_COLORS,
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.6},
        build=build_shampoo,
    ),
    Category(
        name="body loofah",
        shapes={"puff": "bath puff", "sponge": "loofah sponge"},
        colors=("pink", "light blue", "white", "purple", "green", "yellow", "beige", "orange"),
        materials=("fabric", "plastic"),
        placement=Placement.WALL_MOUNTED,
        rooms={"bathroom": 0.3},
        build=build_body_loofah,
        wall_height=1.3,
    ),
    Category(
        name="cosmetics",
        shapes={
            "perfume": "perfume bottle",
            "lipstick": "lipstick set",
            "palette": "make-up palette",
        },
        colors=("black", "gold", "pink", "red", "white", "silver", "purple"),
        materials=("glass", "plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.3, "bedroom": 0.2},
        build=build_cosmetics,
    ),
    Category(
        name="hair dryer",
        shapes={"compact": "compact hair dryer", "professional": "professional hair dryer"},
        colors=("black", "white", "pink", "purple", "gray", "red", "blue"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"bathroom": 0.15, "bedroom": 0.08},
        build=build_hair_dryer,
    ),
]
