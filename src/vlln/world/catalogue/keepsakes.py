"""Things kept for fun or show: toys, trophies, candlesticks, and masks hung on walls.

Toys, trophies and candlesticks stand on shelves and tables and fit a 0.4 x 0.3 m footprint
at the largest scale; masks hang on the wall with their back on z = 0 (the model's origin is
the bottom centre of the back).
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade, standing_on_floor
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder

PLAIN = material_index("plain")
METAL = material_index("metal")
PLASTIC = material_index("plastic")
DARK = color_rgb("black")
GOLD = color_rgb("gold")
BLOCK_COLORS = ("red", "blue", "yellow", "green", "orange", "purple")


def build_toy(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A sitting teddy bear, a toy car with big wheels, or a little pile of building blocks."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "teddy":
        r = 0.06 * s
        b.sphere((0.0, r, 0.0), 1.0, color, mat, segments=10, scale=(r, r * 1.1, r * 0.9))
        head = (0.0, r * 2.6, 0.0)
        b.sphere(head, r * 0.7, color, mat, segments=10)
        for x in (-1, 1):
            b.sphere((x * r * 0.5, r * 3.15, 0.0), r * 0.25, color, mat, segments=6)
            b.sphere(
                (x * r * 0.95, r * 1.3, r * 0.2),
                1.0,
                color,
                mat,
                segments=6,
                scale=(r * 0.28, r * 0.5, r * 0.28),
            )
            b.sphere(
                (x * r * 0.55, r * 0.3, r * 0.7),
                1.0,
                color,
                mat,
                segments=6,
                scale=(r * 0.32, r * 0.3, r * 0.5),
            )
            b.sphere((x * r * 0.25, r * 2.75, r * 0.62), r * 0.07, DARK, PLAIN, segments=4)
        b.sphere(
            (0.0, r * 2.45, r * 0.6),
            1.0,
            shade(color, 1.35),
            mat,
            segments=6,
            scale=(r * 0.3, r * 0.22, r * 0.2),
        )
        b.sphere((0.0, r * 2.5, r * 0.78), r * 0.08, DARK, PLAIN, segments=4)
        return ObjectModel(standing_on_floor(b.build()))
    if style.shape == "car":
        w, d = 0.08 * s, 0.16 * s
        b.box((0.0, 0.04 * s, 0.0), (w, 0.035 * s, d), color, mat)
        b.box((0.0, 0.07 * s, -0.01 * s), (w * 0.85, 0.03 * s, d * 0.5), color, mat)
        b.box(
            (0.0, 0.07 * s, -0.01 * s),
            (w * 0.87, 0.02 * s, d * 0.4),
            color_rgb("light blue"),
            material_index("glass"),
        )
        for wheel_x in (-w / 2 - 0.01 * s, w / 2):
            for z in (-d * 0.3, d * 0.3):
                b.cylinder(
                    (wheel_x, 0.022 * s, z),
                    0.022 * s,
                    0.01 * s,
                    DARK,
                    PLASTIC,
                    segments=8,
                    axis="x",
                )
        return ObjectModel(b.build())
    edge = 0.05 * s
    count = int(rng.integers(4, 7))
    spots = [(-1.0, 0.0), (0.0, 0.0), (1.0, 0.0), (-0.5, 1.0), (0.5, 1.0), (0.0, 2.0)]
    for k in range(count):
        sx, level = spots[k]
        tint = color if k == 0 else color_rgb(BLOCK_COLORS[int(rng.integers(len(BLOCK_COLORS)))])
        jitter = float(rng.uniform(-0.004, 0.004)) * s
        b.box(
            (sx * edge * 1.05 + jitter, edge * (level + 0.5), jitter),
            (edge, edge, edge),
            tint,
            mat,
            yaw=float(rng.uniform(-0.2, 0.2)),
        )
    return ObjectModel(b.build())


def build_trophy(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A cup on a stem with two handles, or a star on a column, on a dark plinth."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    plinth = 0.04 * s
    b.box(
        (0.0, plinth / 2, 0.0),
        (0.09 * s, plinth, 0.09 * s),
        color_rgb("dark brown"),
        material_index("wood"),
    )
    b.box((0.0, plinth * 0.5, 0.0455 * s), (0.05 * s, 0.014 * s, 0.001), GOLD, METAL)
    if style.shape == "cup":
        stem = float(rng.uniform(0.05, 0.07)) * s
        b.cylinder(
            (0.0, plinth, 0.0), 0.03 * s, 0.012 * s, color, mat, segments=10, radius_top=0.008 * s
        )
        b.cylinder((0.0, plinth, 0.0), 0.008 * s, stem, color, mat, segments=8)
        top = plinth + stem
        b.cylinder(
            (0.0, top, 0.0), 0.015 * s, 0.09 * s, color, mat, segments=12, radius_top=0.05 * s
        )
        b.cylinder(
            (0.0, top + 0.09 * s, 0.0), 0.045 * s, 0.001, shade(color, 0.5), mat, segments=12
        )
        for side in (0.0, math.pi):
            x = 0.04 * s * (1 if side == 0.0 else -1)
            arc = (-math.pi / 2, math.pi / 2) if side == 0.0 else (math.pi / 2, 3 * math.pi / 2)
            ring(
                b,
                (x, top + 0.055 * s, 0.0),
                0.025 * s,
                0.006 * s,
                0.008 * s,
                color,
                mat,
                segments=6,
                arc=arc,
            )
        return ObjectModel(b.build())
    column = float(rng.uniform(0.1, 0.13)) * s
    b.box((0.0, plinth + column / 2, 0.0), (0.025 * s, column, 0.025 * s), color, mat)
    center = np.array((0.0, plinth + column + 0.045 * s, 0.0))
    points = []
    for k in range(10):
        radius = (0.05 if k % 2 == 0 else 0.02) * s
        angle = math.pi / 2 + k * math.pi / 5
        points.append(center + radius * np.array((math.cos(angle), math.sin(angle), 0.0)))
    star = np.array(points)
    for side in (1.0, -1.0):  # the front and back faces of a flat star, wound to face out
        offset = np.array((0.0, 0.0, side * 0.006 * s))
        fan = np.stack([np.tile(center, (10, 1)), star, np.roll(star, -1, axis=0)], axis=1)
        corners = (fan if side > 0 else fan[:, ::-1]).reshape(-1, 3) + offset
        normals = np.tile((0.0, 0.0, side), (len(corners), 1))
        b.add_triangles(corners, normals, corners[:, :2], color, mat)
    return ObjectModel(b.build())


def build_candlestick(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A turned holder with one tall candle, or a three-armed candelabra."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    wax, flame = color_rgb("cream"), color_rgb("yellow")
    b = MeshBuilder()
    b.cylinder((0.0, 0.0, 0.0), 0.05 * s, 0.015 * s, color, mat, segments=10, radius_top=0.03 * s)
    stem = float(rng.uniform(0.13, 0.17)) * s
    b.cylinder((0.0, 0.015 * s, 0.0), 0.01 * s, stem, color, mat, segments=8)
    b.sphere((0.0, 0.015 * s + stem * 0.4, 0.0), 0.018 * s, color, mat, segments=6)
    top = 0.015 * s + stem
    cups = [0.0]
    if style.shape == "candelabra":
        cups = [-0.08 * s, 0.0, 0.08 * s]
        ring(
            b,
            (0.0, top, 0.0),
            0.08 * s,
            0.008 * s,
            0.01 * s,
            color,
            mat,
            segments=6,
            arc=(math.pi, 2 * math.pi),
        )
        b.cylinder(
            (0.0, top - 0.005 * s, 0.0), 0.01 * s, 0.005 * s + 0.08 * s, color, mat, segments=8
        )
    for x in cups:
        y = top + (0.08 * s if x == 0.0 and len(cups) == 3 else 0.0)
        b.cylinder((x, y, 0.0), 0.012 * s, 0.015 * s, color, mat, segments=6, radius_top=0.022 * s)
        candle = 0.1 * s
        b.cylinder((x, y + 0.015 * s, 0.0), 0.011 * s, candle, wax, PLAIN, segments=6)
        b.sphere(
            (x, y + 0.015 * s + candle + 0.012 * s, 0.0),
            1.0,
            flame,
            PLAIN,
            segments=6,
            scale=(0.006 * s, 0.013 * s, 0.006 * s),
        )
    return ObjectModel(b.build())


def _hung(mesh: Mesh) -> Mesh:
    """The model moved so that its back touches the wall (z = 0) and its bottom is at y = 0."""
    lo, _ = mesh.bounds()
    return mesh.transformed(0.0, (0.0, -float(lo[1]), -float(lo[2])))


def build_mask(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wall mask: a long carved tribal face, or a carnival half-mask with feathers."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "tribal":
        w, h, d = 0.11 * s, 0.2 * s, 0.04 * s
        b.sphere((0.0, h, d), 1.0, color, mat, segments=10, scale=(w, h, d))
        for x in (-0.04 * s, 0.04 * s):
            b.box((x, h * 1.25, 2 * d - 0.004 * s), (0.035 * s, 0.014 * s, 0.02 * s), DARK, PLAIN)
        beam(
            b,
            (0.0, h * 1.2, 1.8 * d),
            (0.0, h * 0.85, 2.2 * d),
            0.02 * s,
            0.02 * s,
            shade(color, 0.8),
            mat,
        )
        b.box((0.0, h * 0.55, 1.85 * d), (0.05 * s, 0.02 * s, 0.02 * s), DARK, PLAIN)
        for k in range(int(rng.integers(3, 6))):
            b.box(
                (0.0, h * (0.25 + 0.05 * k), 1.5 * d),
                (0.08 * s - 0.01 * s * k, 0.006 * s, 0.02 * s),
                shade(color, 0.6),
                mat,
            )
        return ObjectModel(_hung(b.build()))
    w, h, d = 0.13 * s, 0.06 * s, 0.025 * s
    y0 = 0.08 * s
    b.sphere((0.0, y0, d), 1.0, color, mat, segments=10, scale=(w, h, d))
    for x in (-0.055 * s, 0.055 * s):
        b.sphere(
            (x, y0 + 0.008 * s, 1.75 * d),
            1.0,
            DARK,
            PLAIN,
            segments=6,
            scale=(0.03 * s, 0.015 * s, 0.008 * s),
        )
    rim = (w * 1.07, h * 1.15, d * 0.9)
    b.sphere((0.0, y0, rim[2]), 1.0, GOLD, METAL, segments=10, scale=rim)
    feathers = (color_rgb("purple"), color_rgb("teal"), GOLD)
    root = (w * 0.75, y0 + 0.03 * s, d * 0.6)
    for k in range(int(rng.integers(3, 6))):
        angle = math.radians(35.0 + 14.0 * k)
        tip = (root[0] + 0.12 * s * math.cos(angle), root[1] + 0.12 * s * math.sin(angle), root[2])
        beam(b, root, tip, 0.018 * s, 0.003 * s, feathers[k % 3], PLAIN, side=(0.0, 0.0, 1.0))
    beam(b, (-w * 0.7, y0 - 0.04 * s, d), (-w * 1.05, 0.0, d), 0.008 * s, 0.008 * s, GOLD, METAL)
    return ObjectModel(_hung(b.build()))


CATEGORIES: list[Category] = [
    Category(
        name="toy",
        shapes={"teddy": "teddy bear", "car": "toy car", "blocks": "toy blocks"},
        colors=("brown", "beige", "red", "blue", "yellow", "pink", "green", "white"),
        materials=("fabric", "plastic", "wood"),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.3, "living room": 0.15},
        build=build_toy,
    ),
    Category(
        name="trophy",
        shapes={"cup": "trophy cup", "star": "star trophy"},
        colors=("gold", "silver", "orange"),
        materials=("metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.15, "living room": 0.1, "bedroom": 0.08},
        build=build_trophy,
    ),
    Category(
        name="candlestick",
        shapes={"single": "single candlestick", "candelabra": "candelabra"},
        colors=("silver", "gold", "black", "white", "brown"),
        materials=("metal", "wood", "glass", "ceramic"),
        placement=Placement.ON_SURFACE,
        rooms={"dining room": 0.3, "living room": 0.15},
        build=build_candlestick,
    ),
    Category(
        name="mask",
        shapes={"tribal": "tribal mask", "carnival": "carnival mask"},
        colors=("brown", "dark brown", "white", "gold", "black", "red"),
        materials=("wood", "plastic", "plain"),
        placement=Placement.WALL_MOUNTED,
        rooms={"living room": 0.12, "corridor": 0.05, "study": 0.06},
        build=build_mask,
        wall_height=1.5,
    ),
]
