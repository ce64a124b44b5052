"""Cooking and serving things: pans, knives, seasoning, trays and pitchers.

Every model stands on a counter, a stove or a table and fits a 0.4 x 0.3 m footprint at the
largest scale.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, facing_polygon, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

PLAIN = material_index("plain")
METAL = material_index("metal")
PLASTIC = material_index("plastic")
SILVER = color_rgb("silver")
BLACK = color_rgb("black")
SPICE_COLORS = ("red", "orange", "yellow", "brown", "dark green", "dark brown", "beige")


def _vessel(b: MeshBuilder, r: float, h: float, color: Rgb, mat: int, top: float = 0.0) -> None:
    """An open round vessel whose dark inside shows at the rim."""
    b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=12, radius_top=top or r)
    b.cylinder((0.0, h, 0.0), (top or r) * 0.9, 0.001, shade(color, 0.45), mat, segments=12)


def build_pan(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A shallow frying pan or a deep saucepan with a lid, each with a long straight handle."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    handle = color_rgb("black" if style.color != "black" else "dark brown")
    if style.shape == "frying":
        r, h = float(rng.uniform(0.095, 0.105)) * s, 0.035 * s
        _vessel(b, r * 0.85, h, color, mat, top=r)
    else:
        r, h = 0.075 * s, 0.09 * s
        b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=12)
        b.cylinder(
            (0.0, h, 0.0), r * 1.02, 0.012 * s, SILVER, METAL, segments=12, radius_top=r * 0.5
        )
        b.sphere((0.0, h + 0.018 * s, 0.0), 0.012 * s, handle, PLASTIC, segments=6)
    y = h * 0.8
    beam(b, (r * 0.95, y, 0.0), (r + 0.04 * s, y + 0.008 * s, 0.0), 0.014 * s, 0.01 * s, color, mat)
    beam(
        b,
        (r + 0.04 * s, y + 0.008 * s, 0.0),
        (r + 0.13 * s, y + 0.025 * s, 0.0),
        0.024 * s,
        0.016 * s,
        handle,
        PLASTIC,
    )
    return ObjectModel(b.build())


def _blade(b: MeshBuilder, start: tuple[float, float, float], length: float, width: float) -> None:
    """A flat steel blade lying along +x from ``start``, tapering to a point at its tip."""
    x, y, z = start
    up = np.array((0.0, 1.0, 0.0))
    corners: list[NDArray[np.float64]] = [
        np.array(c)
        for c in (
            (x, y, z - width / 2),
            (x + length, y, z),
            (x + length * 0.8, y, z + width / 2),
            (x, y, z + width / 2),
        )
    ]
    facing_polygon(b, corners, up, SILVER, METAL)
    facing_polygon(b, corners, -up, SILVER, METAL)


def build_knife(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A slanted block with knife handles sticking out, or a kitchen knife lying flat."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "kitchen":
        length = float(rng.uniform(0.18, 0.21)) * s
        b.box((-0.055 * s, 0.01 * s, 0.0), (0.11 * s, 0.02 * s, 0.024 * s), color, mat)
        for x in (-0.085 * s, -0.03 * s):
            b.cylinder((x, 0.02 * s, 0.0), 0.004 * s, 0.001, SILVER, METAL, segments=6)
        _blade(b, (0.0, 0.004 * s, 0.0), length, 0.045 * s)
        return ObjectModel(b.build())
    w, d, h = 0.11 * s, 0.16 * s, 0.2 * s
    for x in (-w / 2, w / 2):
        facing_polygon(
            b,
            [
                np.array(p)
                for p in ((x, 0.0, -d / 2), (x, 0.0, d / 2), (x, h * 0.45, d / 2), (x, h, -d / 2))
            ],
            np.array((np.sign(x), 0.0, 0.0)),
            color,
            mat,
        )
    b.box((0.0, h / 2, -d / 2 + 0.001), (w, h, 0.002), color, mat, faces="-z")
    b.box((0.0, h * 0.45 / 2, d / 2 - 0.001), (w, h * 0.45, 0.002), color, mat, faces="+z")
    top = [
        np.array(p)
        for p in (
            (-w / 2, h * 0.45, d / 2),
            (w / 2, h * 0.45, d / 2),
            (w / 2, h, -d / 2),
            (-w / 2, h, -d / 2),
        )
    ]
    facing_polygon(b, top, np.array((0.0, 1.0, 1.0)), color, mat)
    handles = SILVER if style.color in ("black", "dark brown") else BLACK
    n = int(rng.integers(3, 6))
    for k in range(n):  # handles stick out of the slanted top, alternately front and back
        x = (k - (n - 1) / 2) * w * 0.8 / max(n - 1, 1)
        back = 0.35 + 0.5 * (k % 2)  # how far along the top from its front edge
        y, z = h * 0.45 + h * 0.55 * back, d / 2 - d * back
        beam(b, (x, y, z), (x, y + 0.07 * s, z + 0.045 * s), 0.018 * s, 0.026 * s, handles, PLASTIC)
    return ObjectModel(b.build())


def build_seasoning(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Salt and pepper shakers, a tall pepper grinder, or a small rack of spice jars."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "shakers":
        for x, body in ((-0.03 * s, color), (0.03 * s, shade(color, 0.55))):
            b.cylinder(
                (x, 0.0, 0.0), 0.022 * s, 0.07 * s, body, mat, segments=10, radius_top=0.018 * s
            )
            b.sphere(
                (x, 0.07 * s, 0.0),
                1.0,
                SILVER,
                METAL,
                segments=8,
                scale=(0.018 * s, 0.015 * s, 0.018 * s),
                upper_half_only=True,
            )
        return ObjectModel(b.build())
    if style.shape == "grinder":
        h = float(rng.uniform(0.17, 0.21)) * s
        b.cylinder(
            (0.0, 0.0, 0.0), 0.028 * s, h * 0.45, color, mat, segments=10, radius_top=0.02 * s
        )
        b.cylinder(
            (0.0, h * 0.45, 0.0), 0.02 * s, h * 0.45, color, mat, segments=10, radius_top=0.026 * s
        )
        b.cylinder(
            (0.0, h * 0.9, 0.0), 0.026 * s, h * 0.06, color, mat, segments=10, radius_top=0.012 * s
        )
        b.sphere((0.0, h * 0.97, 0.0), 0.014 * s, SILVER, METAL, segments=6)
        return ObjectModel(b.build())
    w, d = 0.26 * s, 0.07 * s
    b.box((0.0, 0.006 * s, 0.0), (w, 0.012 * s, d), color, mat)
    b.box((0.0, 0.06 * s, -d / 2 + 0.005 * s), (w, 0.12 * s, 0.01 * s), color, mat)
    for x in (-1, 1):
        b.box((x * (w / 2 - 0.005 * s), 0.04 * s, 0.0), (0.01 * s, 0.08 * s, d), color, mat)
    for k in range(5):
        x = (k - 2) * w * 0.19
        spice = color_rgb(SPICE_COLORS[int(rng.integers(len(SPICE_COLORS)))])
        b.cylinder((x, 0.012 * s, 0.005 * s), 0.019 * s, 0.06 * s, spice, PLAIN, segments=8)
        b.cylinder((x, 0.072 * s, 0.005 * s), 0.02 * s, 0.015 * s, BLACK, PLASTIC, segments=8)
    return ObjectModel(b.build())


def build_tray(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A flat serving tray with a low rim: rectangular with cut-out handles, or round."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    t, rim = 0.008 * s, 0.03 * s
    if style.shape == "round":
        r = float(rng.uniform(0.12, 0.13)) * s
        b.cylinder((0.0, 0.0, 0.0), r * 0.97, t, color, mat, segments=14)
        ring(
            b,
            (0.0, rim / 2, 0.0),
            r,
            0.008 * s,
            rim,
            shade(color, 0.85),
            mat,
            axis="y",
            segments=14,
        )
        return ObjectModel(b.build())
    w, d = 0.34 * s, float(rng.uniform(0.22, 0.25)) * s
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    for z in (-1, 1):
        b.box((0.0, rim / 2, z * (d / 2 - 0.004 * s)), (w, rim, 0.008 * s), shade(color, 0.85), mat)
    for x in (-1, 1):
        b.box((x * (w / 2 - 0.004 * s), rim, 0.0), (0.008 * s, rim * 2, d), shade(color, 0.85), mat)
        b.box(
            (x * (w / 2 - 0.003 * s), rim * 1.35, 0.0),
            (0.01 * s, rim * 0.4, d * 0.35),
            shade(color, 0.3),
            mat,
        )
    return ObjectModel(b.build())


def build_pitcher(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A jug with a pouring lip and a loop handle: tall and tapering, or round-bellied."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    h = float(rng.uniform(0.19, 0.23)) * s
    r = 0.055 * s
    if style.shape == "round":
        b.sphere(
            (0.0, h * 0.38, 0.0), 1.0, color, mat, segments=12, scale=(r * 1.3, h * 0.38, r * 1.3)
        )
        b.cylinder(
            (0.0, h * 0.6, 0.0), r * 0.75, h * 0.4, color, mat, segments=12, radius_top=r * 0.9
        )
    else:
        b.cylinder((0.0, 0.0, 0.0), r * 1.1, h, color, mat, segments=12, radius_top=r * 0.85)
    b.cylinder((0.0, h, 0.0), r * 0.8, 0.001, shade(color, 0.4), mat, segments=12)
    lip = [
        np.array(p)
        for p in (
            (r * 0.6, h, -0.02 * s),
            (r * 0.6, h, 0.02 * s),
            (r * 1.35, h + 0.02 * s, 0.008 * s),
            (r * 1.35, h + 0.02 * s, -0.008 * s),
        )
    ]
    facing_polygon(b, lip, np.array((0.0, 1.0, 0.0)), color, mat)
    ring(
        b,
        (-r * 0.95, h * 0.6, 0.0),
        h * 0.25,
        0.012 * s,
        0.015 * s,
        color,
        mat,
        segments=8,
        arc=(math.pi / 2, 3 * math.pi / 2),
    )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="pan",
        shapes={"frying": "frying pan", "saucepan": "saucepan"},
        colors=("black", "silver", "gray", "dark gray", "red", "orange"),
        materials=("metal", "ceramic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.5},
        build=build_pan,
    ),
    Category(
        name="knife",
        shapes={"block": "knife block", "kitchen": "kitchen knife"},
        colors=("black", "brown", "dark brown", "white", "red", "gray"),
        materials=("wood", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.4, "dining room": 0.05},
        build=build_knife,
    ),
    Category(
        name="seasoning",
        shapes={
            "shakers": "salt and pepper shakers",
            "grinder": "pepper grinder",
            "rack": "spice rack",
        },
        colors=("white", "black", "brown", "silver", "red", "cream", "gray"),
        materials=("wood", "ceramic", "glass", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.5, "dining room": 0.3},
        build=build_seasoning,
    ),
    Category(
        name="tray",
        shapes={"rectangular": "rectangular tray", "round": "round tray"},
        colors=("brown", "black", "silver", "white", "red", "gold", "beige"),
        materials=("wood", "metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.2, "dining room": 0.2, "living room": 0.15},
        build=build_tray,
    ),
    Category(
        name="pitcher",
        shapes={"tall": "tall pitcher", "round": "round pitcher"},
        colors=("white", "light blue", "cream", "blue", "green", "silver", "gray"),
        materials=("glass", "ceramic", "metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.2, "dining room": 0.3},
        build=build_pitcher,
    ),
]
