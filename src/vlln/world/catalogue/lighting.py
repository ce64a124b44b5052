"""Lamps and ceiling lights: a base, a pole or cord, and a shade or bulbs."""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

FABRIC = material_index("fabric")
METAL = material_index("metal")
PLAIN = material_index("plain")
GLASS = material_index("glass")
SHADE_COLORS = ("white", "cream", "beige", "light gray")


def _lamp_shade(rng: np.random.Generator) -> Rgb:
    return color_rgb(SHADE_COLORS[int(rng.integers(len(SHADE_COLORS)))])


def _drum(b: MeshBuilder, y: float, r: float, h: float, color: Rgb) -> None:
    """A fabric lamp shade, a little narrower at the top."""
    b.cylinder((0.0, y, 0.0), r, h, color, FABRIC, segments=12, radius_top=r * 0.8)


def build_floor_lamp(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A base, a pole and a shade: straight, on a tripod, or an arc with a hanging dome."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    shade_color = _lamp_shade(rng)
    h = float(rng.uniform(1.45, 1.65)) * s
    b = MeshBuilder()
    if style.shape == "tripod":
        hub = h * 0.55
        for k in range(3):
            a = 2 * math.pi * k / 3 + math.pi / 2
            foot = (0.3 * s * math.cos(a), 0.015 * s, 0.3 * s * math.sin(a))
            beam(b, foot, (0.0, hub, 0.0), 0.03 * s, 0.03 * s, color, mat)
        b.cylinder((0.0, hub, 0.0), 0.012 * s, h - hub - 0.2 * s, color, mat, segments=6)
        _drum(b, h - 0.3 * s, 0.22 * s, 0.3 * s, shade_color)
        return ObjectModel(standing_on_floor(b.build()))
    if style.shape == "arc":
        b.box(
            (0.0, 0.03 * s, 0.0),
            (0.3 * s, 0.06 * s, 0.3 * s),
            color_rgb("white"),
            material_index("marble"),
        )
        prev = (0.0, 0.06 * s, 0.0)
        for k in range(1, 7):
            a = math.pi / 2 * k / 6
            pt = (0.0, 0.06 * s + (h + 0.2 * s) * math.sin(a) * 0.95, 0.6 * s * (1 - math.cos(a)))
            beam(b, prev, pt, 0.025 * s, 0.025 * s, color, mat)
            prev = pt
        dome_y = prev[1] - 0.22 * s
        b.sphere(
            (0.0, dome_y, prev[2] + 0.02),
            0.2 * s,
            color,
            mat,
            segments=12,
            scale=(1.0, 1.1, 1.0),
            upper_half_only=True,
        )
    else:
        b.cylinder((0.0, 0.0, 0.0), 0.16 * s, 0.03 * s, color, mat, segments=12)
        b.cylinder((0.0, 0.03 * s, 0.0), 0.012 * s, h - 0.2 * s, color, mat, segments=6)
        _drum(b, h - 0.3 * s, 0.2 * s, 0.3 * s, shade_color)
    return ObjectModel(b.build())


def build_table_lamp(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A bedside lamp (round base, neck, drum shade) or a desk lamp on a jointed arm."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "desk":
        b.cylinder((0.0, 0.0, 0.0), 0.07 * s, 0.02 * s, color, mat, segments=10)
        elbow = (0.0, 0.28 * s, -0.06 * s)
        head = (0.0, 0.36 * s, 0.1 * s)
        beam(b, (0.0, 0.02 * s, -0.02 * s), elbow, 0.015 * s, 0.015 * s, color, mat)
        beam(b, elbow, head, 0.015 * s, 0.015 * s, color, mat)
        b.cylinder(
            (0.0, head[1] - 0.1 * s, head[2]),
            0.065 * s,
            0.1 * s,
            color,
            mat,
            segments=10,
            radius_top=0.02 * s,
        )
        return ObjectModel(b.build())
    body_h = float(rng.uniform(0.14, 0.22)) * s
    b.cylinder((0.0, 0.0, 0.0), 0.06 * s, 0.015 * s, color, mat, segments=10)
    b.sphere(
        (0.0, 0.015 * s + body_h / 2, 0.0),
        0.08 * s,
        color,
        mat,
        segments=10,
        scale=(1.0, body_h / (0.16 * s), 1.0),
    )
    b.cylinder((0.0, body_h, 0.0), 0.01 * s, 0.12 * s, color_rgb("silver"), METAL, segments=6)
    _drum(b, body_h + 0.08 * s, 0.125 * s, 0.18 * s, _lamp_shade(rng))
    return ObjectModel(b.build())


def build_ceiling_light(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A ceiling rose with a pendant shade, a flush drum, or a chandelier of candle bulbs."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    bulb = (1.0, 0.95, 0.8)
    b = MeshBuilder()
    if style.shape == "flush":
        b.cylinder(
            (0.0, 0.0, 0.0),
            0.15 * s,
            0.08 * s,
            color_rgb("white"),
            GLASS,
            segments=12,
            radius_top=0.2 * s,
        )
        b.cylinder((0.0, 0.08 * s, 0.0), 0.21 * s, 0.02 * s, color, mat, segments=12)
        return ObjectModel(b.build())
    drop = float(rng.uniform(0.3, 0.5)) * s
    if style.shape == "chandelier":
        hub_y, arm = 0.05 * s, 0.25 * s
        b.sphere((0.0, hub_y, 0.0), 0.05 * s, color, mat, segments=6)
        b.cylinder((0.0, hub_y, 0.0), 0.01 * s, drop, color, mat, segments=6)
        for k in range(5):
            a = 2 * math.pi * k / 5
            end = (arm * math.cos(a), hub_y + 0.06 * s, arm * math.sin(a))
            beam(b, (0.0, hub_y, 0.0), end, 0.015 * s, 0.015 * s, color, mat)
            b.cylinder(end, 0.012 * s, 0.06 * s, color_rgb("white"), PLAIN, segments=5)
            tip = (end[0], end[1] + 0.08 * s, end[2])
            b.sphere(tip, 0.018 * s, bulb, GLASS, segments=4, scale=(1.0, 1.4, 1.0))
        top = hub_y + drop
    else:
        shade_h = 0.2 * s
        b.sphere((0.0, 0.04 * s, 0.0), 0.04 * s, bulb, GLASS, segments=6)
        b.cylinder((0.0, 0.0, 0.0), 0.18 * s, shade_h, color, mat, segments=12, radius_top=0.05 * s)
        b.cylinder((0.0, shade_h, 0.0), 0.006, drop, color_rgb("black"), PLAIN, segments=6)
        top = shade_h + drop
    b.cylinder((0.0, top, 0.0), 0.06 * s, 0.025 * s, color_rgb("white"), PLAIN, segments=10)
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="floor lamp",
        shapes={"straight": "floor lamp", "tripod": "tripod floor lamp", "arc": "arc lamp"},
        colors=("black", "white", "silver", "gold", "brown"),
        materials=("metal", "wood"),
        placement=Placement.CORNER,
        rooms={"living room": 0.6, "bedroom": 0.3, "study": 0.3},
        build=build_floor_lamp,
    ),
    Category(
        name="table lamp",
        shapes={"classic": "bedside lamp", "desk": "desk lamp"},
        colors=("white", "black", "blue", "green", "gold", "gray", "red", "cream"),
        materials=("ceramic", "metal", "glass"),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 1.2, "living room": 0.6, "study": 0.8, "corridor": 0.1},
        build=build_table_lamp,
    ),
    Category(
        name="ceiling light",
        shapes={
            "pendant": "pendant light",
            "flush": "flush ceiling light",
            "chandelier": "chandelier",
        },
        colors=("white", "black", "gold", "silver", "gray"),
        materials=("metal", "glass"),
        placement=Placement.CEILING,
        rooms={
            "living room": 1.2,
            "bedroom": 1.0,
            "kitchen": 1.0,
            "dining room": 1.0,
            "bathroom": 0.8,
            "toilet": 0.7,
            "study": 1.0,
            "corridor": 1.0,
            "storage room": 0.6,
            "gym": 1.0,
        },
        build=build_ceiling_light,
    ),
]
