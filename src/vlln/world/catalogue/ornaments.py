"""Wall decor and ornaments: pictures, clocks, vases, candles and statues.

Wall-mounted models (picture, clock) have their back on z = 0 and their bottom on y = 0, so the
model's origin is the bottom centre of its back; ``wall_height`` is the height of that origin
above the floor.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, facing_quad, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

FOLIAGE = material_index("foliage")
METAL = material_index("metal")
PLAIN = material_index("plain")
FLAME = (1.0, 0.75, 0.2)


def _painting(
    b: MeshBuilder, shape: str, w: float, h: float, y0: float, z: float, rng: np.random.Generator
) -> None:
    """The canvas of a picture as a few flat colour patches (front faces only)."""

    def patch(u0: float, v0: float, u1: float, v1: float, c: Rgb, layer: int = 0) -> None:
        centre = ((u0 + u1) / 2 * w, y0 + (v0 + v1) / 2 * h, z + 0.001 * layer)
        b.box(centre, ((u1 - u0) * w, (v1 - v0) * h, 0.0), c, PLAIN, faces="+z")

    names = ("red", "orange", "yellow", "blue", "teal", "purple", "pink", "green", "navy")
    pick = [color_rgb(names[int(i)]) for i in rng.choice(len(names), 4, replace=False)]
    if shape == "landscape":
        horizon = float(rng.uniform(0.35, 0.55))
        patch(-0.5, horizon, 0.5, 1.0, color_rgb("light blue"))
        patch(-0.5, 0.0, 0.5, horizon, color_rgb("green"))
        patch(-0.3, horizon - 0.05, 0.05, horizon + 0.25, color_rgb("dark green"), 1)
        patch(0.2, 0.72, 0.32, 0.88, color_rgb("yellow"), 1)
    elif shape == "portrait":
        patch(-0.5, 0.0, 0.5, 1.0, pick[0])
        patch(-0.32, 0.0, 0.32, 0.32, pick[1], 1)
        b.sphere(
            (0.0, y0 + 0.55 * h, z),
            0.17 * w,
            color_rgb("beige"),
            PLAIN,
            segments=8,
            scale=(1.0, 1.3, 0.05),
        )
    else:
        patch(-0.5, 0.0, 0.5, 1.0, color_rgb("cream"))
        for k in range(3):
            u0, v0 = float(rng.uniform(-0.45, 0.1)), float(rng.uniform(0.05, 0.6))
            du, dv = float(rng.uniform(0.15, 0.35)), float(rng.uniform(0.15, 0.35))
            patch(u0, v0, u0 + du, v0 + dv, pick[k + 1], k + 1)


def build_picture(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A framed painting: a landscape, a portrait or an abstract of colour blocks."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, h = {"landscape": (0.7, 0.5), "portrait": (0.42, 0.56)}.get(style.shape, (0.5, 0.5))
    k = float(rng.uniform(0.8, 1.25)) * s
    w, h, f, depth = w * k, h * k, 0.04 * s, 0.03
    b = MeshBuilder()
    for x, y, sw, sh in (
        (0.0, f / 2, w, f),
        (0.0, h - f / 2, w, f),
        (-(w - f) / 2, h / 2, f, h - 2 * f),
        ((w - f) / 2, h / 2, f, h - 2 * f),
    ):
        b.box((x, y, depth / 2), (sw, sh, depth), color, mat)
    b.box((0.0, h / 2, 0.005), (w - f, h - f, 0.01), color_rgb("white"), PLAIN)
    _painting(b, style.shape, w - 2 * f, h - 2 * f, f, 0.011, rng)
    return ObjectModel(b.build())


def build_clock(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A white dial with hour marks and two hands, in a round rim or a square frame."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    r = float(rng.uniform(0.13, 0.17)) * s
    depth, black = 0.04 * s, color_rgb("black")
    b = MeshBuilder()
    if style.shape == "square":
        b.box((0.0, r, depth / 4), (2 * r, 2 * r, depth / 2), color, mat)
    else:
        ring(b, (0.0, r, depth / 2), r, 0.02 * s, depth, color, mat, segments=16)
    face = color_rgb("cream") if style.color == "white" else color_rgb("white")
    b.cylinder((0.0, r, 0.0), r - 0.015 * s, depth * 0.7, face, PLAIN, segments=16, axis="z")
    zf = depth * 0.7 + 0.001
    for k in range(12):
        a = 2 * math.pi * k / 12
        radial, across = (
            np.array([math.sin(a), math.cos(a), 0.0]),
            np.array([math.cos(a), -math.sin(a), 0.0]),
        )
        length, width = (0.025 * s, 0.006) if k % 3 else (0.035 * s, 0.012)
        corner = np.array([0.0, r, zf]) + radial * (r - 0.03 * s - length) - across * width / 2
        facing_quad(
            b, corner, radial * length, across * width, np.array([0.0, 0.0, 1.0]), black, PLAIN
        )
    hour, minute = float(rng.uniform(0, 2 * math.pi)), float(rng.uniform(0, 2 * math.pi))
    for a, length in ((hour, 0.5), (minute, 0.78)):
        tip = ((r * length) * math.sin(a), r + (r * length) * math.cos(a), zf + 0.004)
        beam(b, (0.0, r, zf + 0.004), tip, 0.012 * s, 0.003, black, METAL, side=(1.0, 0.0, 0.0))
    return ObjectModel(b.build())


def build_vase(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall vase with a flared mouth, a round one with a neck, or a vase of flowers."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "round":
        r = float(rng.uniform(0.07, 0.1)) * s
        b.sphere((0.0, r, 0.0), r, color, mat, segments=10)
        b.cylinder(
            (0.0, r * 1.6, 0.0), r * 0.3, r * 0.8, color, mat, segments=8, radius_top=r * 0.45
        )
        return ObjectModel(b.build())
    h = float(rng.uniform(0.22, 0.32)) * s
    r = 0.06 * s
    b.cylinder((0.0, 0.0, 0.0), r * 0.8, h * 0.7, color, mat, segments=10, radius_top=r)
    b.cylinder((0.0, h * 0.7, 0.0), r, h * 0.15, color, mat, segments=10, radius_top=r * 0.5)
    b.cylinder(
        (0.0, h * 0.85, 0.0), r * 0.5, h * 0.15, color, mat, segments=10, radius_top=r * 0.75
    )
    if style.shape == "flowers":
        blossoms = ("red", "yellow", "pink", "white", "orange", "purple")
        for k in range(5):
            a = 2 * math.pi * k / 5 + float(rng.uniform(-0.3, 0.3))
            lean = float(rng.uniform(0.1, 0.35))
            length = float(rng.uniform(0.15, 0.25)) * s
            tip = (
                length * math.sin(lean) * math.cos(a),
                h + length * math.cos(lean),
                length * math.sin(lean) * math.sin(a),
            )
            beam(b, (0.0, h * 0.8, 0.0), tip, 0.006, 0.006, color_rgb("green"), FOLIAGE)
            bloom = color_rgb(blossoms[int(rng.integers(len(blossoms)))])
            b.sphere(tip, 0.03 * s, bloom, FOLIAGE, segments=4, scale=(1.0, 0.7, 1.0))
    return ObjectModel(b.build())


def build_candle(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wax pillar, or a thin taper in a metal candlestick, each with a lit flame."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "taper":
        holder = color_rgb("gold" if rng.random() < 0.5 else "silver")
        b.cylinder((0.0, 0.0, 0.0), 0.045 * s, 0.015 * s, holder, METAL, segments=10)
        b.cylinder((0.0, 0.015 * s, 0.0), 0.012 * s, 0.09 * s, holder, METAL, segments=6)
        b.cylinder((0.0, 0.1 * s, 0.0), 0.02 * s, 0.02 * s, holder, METAL, segments=8)
        y0, r, h = 0.12 * s, 0.011 * s, float(rng.uniform(0.16, 0.22)) * s
    else:
        y0, r, h = 0.0, float(rng.uniform(0.03, 0.045)) * s, float(rng.uniform(0.08, 0.15)) * s
    b.cylinder((0.0, y0, 0.0), r, h, color, mat, segments=10)
    b.box((0.0, y0 + h + 0.006, 0.0), (0.002, 0.012, 0.002), color_rgb("black"), PLAIN)
    b.sphere(
        (0.0, y0 + h + 0.022 * s, 0.0), 0.008 * s, FLAME, PLAIN, segments=6, scale=(1.0, 2.0, 1.0)
    )
    return ObjectModel(b.build())


def build_statue(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A sculpture on a plinth: a bust, a standing figure, or stacked abstract blocks."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    plinth = 0.05 * s
    b.box((0.0, plinth / 2, 0.0), (0.16 * s, plinth, 0.14 * s), shade(color, 0.8), mat)
    if style.shape == "bust":
        b.sphere(
            (0.0, plinth + 0.06 * s, 0.0), 0.1 * s, color, mat, segments=10, scale=(1.0, 0.6, 0.55)
        )
        b.cylinder((0.0, plinth + 0.08 * s, 0.0), 0.025 * s, 0.08 * s, color, mat, segments=8)
        b.sphere(
            (0.0, plinth + 0.2 * s, 0.005),
            0.055 * s,
            color,
            mat,
            segments=10,
            scale=(0.85, 1.1, 1.0),
        )
    elif style.shape == "figure":
        leg_h, body_h = 0.12 * s, 0.1 * s
        for x in (-1, 1):
            b.box(
                (x * 0.018 * s, plinth + leg_h / 2, 0.0), (0.025 * s, leg_h, 0.03 * s), color, mat
            )
            arm_top = (x * 0.045 * s, plinth + leg_h + body_h * 0.9, 0.0)
            beam(
                b,
                arm_top,
                (x * 0.06 * s, plinth + leg_h, 0.01 * s),
                0.018 * s,
                0.018 * s,
                color,
                mat,
            )
        b.box((0.0, plinth + leg_h + body_h / 2, 0.0), (0.07 * s, body_h, 0.035 * s), color, mat)
        b.sphere((0.0, plinth + leg_h + body_h + 0.03 * s, 0.0), 0.028 * s, color, mat, segments=8)
    else:
        y = plinth
        for k in range(4):
            size = (0.1 - 0.015 * k) * s
            b.box(
                (0.0, y + size * 0.4, 0.0),
                (size, size * 0.8, size * 0.6),
                color,
                mat,
                yaw=float(rng.uniform(0.0, math.pi)),
            )
            y += size * 0.8
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="picture",
        shapes={
            "landscape": "landscape painting",
            "portrait": "portrait",
            "abstract": "abstract painting",
        },
        colors=("black", "gold", "brown", "white", "silver", "dark brown"),
        materials=("wood", "metal", "plastic"),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "living room": 2.0,
            "bedroom": 1.2,
            "dining room": 1.2,
            "corridor": 1.0,
            "study": 0.8,
            "kitchen": 0.4,
            "bathroom": 0.3,
            "toilet": 0.3,
            "gym": 0.2,
        },
        build=build_picture,
        wall_height=1.25,
    ),
    Category(
        name="clock",
        shapes={"round": "round wall clock", "square": "square wall clock"},
        colors=("black", "white", "silver", "gold", "brown", "red"),
        materials=("plastic", "metal", "wood"),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "kitchen": 0.5,
            "living room": 0.5,
            "dining room": 0.3,
            "study": 0.3,
            "bedroom": 0.2,
            "corridor": 0.15,
            "gym": 0.2,
        },
        build=build_clock,
        wall_height=1.7,
    ),
    Category(
        name="vase",
        shapes={"tall": "tall vase", "round": "round vase", "flowers": "vase of flowers"},
        colors=("white", "blue", "green", "red", "teal", "cream", "black", "gold"),
        materials=("ceramic", "glass"),
        placement=Placement.ON_SURFACE,
        rooms={
            "living room": 0.6,
            "dining room": 0.5,
            "bedroom": 0.2,
            "corridor": 0.2,
            "study": 0.1,
        },
        build=build_vase,
    ),
    Category(
        name="candle",
        shapes={"pillar": "pillar candle", "taper": "taper candle"},  # "candlestick" is a category
        colors=("white", "cream", "red", "beige", "purple", "yellow"),
        materials=("plain",),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.4, "dining room": 0.5, "bedroom": 0.2, "bathroom": 0.3},
        build=build_candle,
    ),
    Category(
        name="statue",
        shapes={"bust": "bust", "figure": "figurine", "abstract": "abstract sculpture"},
        colors=("white", "gray", "black", "gold", "beige", "brown"),
        materials=("marble", "metal", "ceramic", "wood"),
        placement=Placement.ON_SURFACE,
        rooms={
            "living room": 0.3,
            "study": 0.15,
            "corridor": 0.1,
            "dining room": 0.1,
            "bedroom": 0.05,
        },
        build=build_statue,
    ),
]
