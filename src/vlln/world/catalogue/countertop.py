"""Countertop appliances: microwave, kettle, toaster and coffee machine.

All stand on a counter or table, so each fits a 0.4 x 0.3 m footprint at the largest scale.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

SMALL_APPLIANCE_COLORS = ("white", "silver", "black", "red", "cream", "gray")

METAL = material_index("metal")
GLASS = material_index("glass")
PLASTIC = material_index("plastic")
BLACK = color_rgb("black")
DARK = color_rgb("dark gray")


def build_microwave(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A box with a dark window door and a side panel of buttons or dials."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, h = 0.34 * s, 0.235 * s, (0.2 + float(rng.uniform(0.0, 0.02))) * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    door_w = w * 0.7
    b.box(
        (-w / 2 + door_w / 2 + 0.01, h / 2, zf + 0.005),
        (door_w - 0.02, h - 0.03, 0.01),
        shade(color, 0.9),
        mat,
    )
    b.box((-w / 2 + door_w / 2, h / 2, zf + 0.011), (door_w * 0.7, h * 0.6, 0.003), BLACK, GLASS)
    px = w / 2 - (w - door_w) / 2
    if style.shape == "dial":
        for y in (0.7, 0.35):
            b.cylinder((px, h * y, zf), 0.02 * s, 0.015 * s, DARK, PLASTIC, segments=8, axis="z")
    else:
        b.box((px, h * 0.8, zf + 0.002), (w * 0.2, h * 0.1, 0.004), BLACK, GLASS)
        for row in range(3):
            for col in (-1, 1):
                b.box(
                    (px + col * w * 0.05, h * (0.58 - 0.14 * row), zf + 0.003),
                    (w * 0.07, h * 0.08, 0.006),
                    DARK,
                    PLASTIC,
                    faces="+z+y",
                )
    return ObjectModel(b.build())


def build_kettle(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A jug with a spout and a handle: electric on its base plate, or a stovetop kettle."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "electric":
        b.cylinder((0.0, 0.0, 0.0), 0.085 * s, 0.02 * s, DARK, PLASTIC, segments=10)
        body_h = (0.19 + float(rng.uniform(0.0, 0.03))) * s
        y0, r0, r1 = 0.02 * s, 0.075 * s, 0.062 * s
        b.cylinder((0.0, y0, 0.0), r0, body_h, color, mat, segments=10, radius_top=r1)
        top = y0 + body_h
        b.cylinder((0.0, top, 0.0), r1 * 0.7, 0.012 * s, shade(color, 0.8), mat, segments=10)
        ring(
            b,
            (-r0 * 0.9, y0 + body_h * 0.55, 0.0),
            body_h * 0.42,
            0.02 * s,
            0.025 * s,
            DARK,
            PLASTIC,
            segments=8,
            arc=(math.pi / 2, 3 * math.pi / 2),
        )
        beam(
            b,
            (r0 * 0.8, y0 + body_h * 0.7, 0.0),
            (r0 + 0.035 * s, top + 0.01 * s, 0.0),
            0.03 * s,
            0.02 * s,
            color,
            mat,
            side=(0.0, 0.0, 1.0),
        )
        return ObjectModel(b.build())
    body_h, r0, r1 = 0.13 * s, 0.1 * s, 0.055 * s
    b.cylinder((0.0, 0.0, 0.0), r0, body_h, color, mat, segments=12, radius_top=r1)
    b.cylinder((0.0, body_h, 0.0), 0.03 * s, 0.02 * s, BLACK, PLASTIC, segments=8)
    ring(
        b,
        (0.0, body_h, 0.0),
        0.075 * s,
        0.015 * s,
        0.02 * s,
        BLACK,
        PLASTIC,
        segments=8,
        arc=(0.15, math.pi - 0.15),
    )
    beam(
        b,
        (r0 * 0.6, body_h * 0.35, 0.0),
        (r0 + 0.05 * s, body_h * 0.95, 0.0),
        0.025 * s,
        0.02 * s,
        color,
        mat,
        side=(0.0, 0.0, 1.0),
    )
    return ObjectModel(b.build())


def build_toaster(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A box with dark bread slots on top and a lever on its side."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    four = style.shape == "four-slice"
    w, d, h = (0.3 if four else 0.27) * s, (0.24 if four else 0.17) * s, 0.19 * s
    b = MeshBuilder()
    b.box((0.0, 0.005, 0.0), (w * 0.9, 0.01, d * 0.9), BLACK, PLASTIC)
    b.box((0.0, 0.01 + (h - 0.03) / 2, 0.0), (w, h - 0.03, d), color, mat)
    b.box((0.0, h - 0.01, 0.0), (w * 0.95, 0.02, d * 0.92), color, mat)
    slot_len = w * 0.4 if four else w * 0.7
    for x in (-w * 0.23, w * 0.23) if four else (0.0,):
        for z in (-d * 0.18, d * 0.18):
            b.box((x, h + 0.001, z), (slot_len, 0.002, 0.022 * s), BLACK, PLASTIC, faces="+y")
    lever_y = h * float(rng.uniform(0.55, 0.8))
    b.box((w / 2 + 0.015, lever_y, 0.0), (0.03, 0.015, 0.035 * s), DARK, PLASTIC)
    b.cylinder((w / 2, h * 0.3, 0.0), 0.015 * s, 0.015, DARK, PLASTIC, segments=8, axis="x")
    return ObjectModel(b.build())


def build_coffee_machine(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tower over a drip tray: espresso head with a cup, or a drip brewer with a carafe."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.2 * s, 0.25 * s
    h = (0.33 + float(rng.uniform(0.0, 0.04))) * s
    tower_d, head_h = 0.1 * s, 0.08 * s
    b = MeshBuilder()
    b.box((0.0, 0.015 * s, 0.0), (w, 0.03 * s, d), DARK, METAL)
    b.box((0.0, h / 2, -d / 2 + tower_d / 2), (w, h, tower_d), color, mat)
    b.box((0.0, h - head_h / 2, 0.0), (w, head_h, d), color, mat)
    zf = d / 2
    for k in range(3):
        b.box(
            (w * (0.25 * k - 0.25), h - head_h / 2, zf + 0.003),
            (0.025, 0.015, 0.006),
            color_rgb("light gray"),
            PLASTIC,
            faces="+z+y",
        )
    under = h - head_h
    if style.shape == "espresso":
        b.cylinder((0.0, under - 0.035 * s, 0.03 * s), 0.02 * s, 0.035 * s, DARK, METAL, segments=8)
        b.cylinder(
            (0.0, 0.03 * s, 0.03 * s),
            0.03 * s,
            0.06 * s,
            color_rgb("white"),
            material_index("ceramic"),
            segments=8,
            radius_top=0.035 * s,
        )
    else:
        b.cylinder(
            (0.0, 0.03 * s, 0.035 * s),
            0.065 * s,
            under * 0.75,
            color_rgb("light blue"),
            GLASS,
            segments=10,
            radius_top=0.05 * s,
        )
        b.box(
            (0.075 * s, 0.03 * s + under * 0.4, 0.035 * s),
            (0.02 * s, under * 0.45, 0.02 * s),
            BLACK,
            PLASTIC,
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="microwave",
        shapes={"digital": "microwave oven", "dial": "dial microwave"},
        colors=("white", "silver", "black", "gray", "cream"),
        materials=("metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.8, "dining room": 0.05},
        build=build_microwave,
    ),
    Category(
        name="kettle",
        shapes={"electric": "electric kettle", "stovetop": "stovetop kettle"},
        colors=SMALL_APPLIANCE_COLORS,
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.7},
        build=build_kettle,
    ),
    Category(
        name="toaster",
        shapes={"two-slice": "toaster", "four-slice": "four-slice toaster"},
        colors=SMALL_APPLIANCE_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.5, "dining room": 0.05},
        build=build_toaster,
    ),
    Category(
        name="coffee machine",
        shapes={"espresso": "espresso machine", "drip": "drip coffee maker"},
        colors=("black", "silver", "red", "white", "gray"),
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.6, "dining room": 0.1, "study": 0.05},
        build=build_coffee_machine,
    ),
]
