"""More furniture: footstools, vanities, countertops, stands, ladders, carts and pool tables."""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import (
    PAINT_COLORS,
    WOOD_COLORS,
    add_carcass,
    add_fronts,
    add_legs,
    add_top,
    worktop_finish,
)
from vlln.world.catalogue.parts import beam, shade, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

WOOD = material_index("wood")
METAL = material_index("metal")
PLASTIC = material_index("plastic")
CERAMIC = material_index("ceramic")
FABRIC = material_index("fabric")
BLACK = color_rgb("black")
SILVER = color_rgb("silver")
WHITE = color_rgb("white")


def build_footstool(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A small padded stool on splayed wooden legs, or a two-step plastic step stool."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "step":
        w, d = 0.42 * s, 0.4 * s
        for k, (y, z0) in enumerate(((0.22 * s, 0.0), (0.42 * s, -d / 2))):
            depth = d / 2 if k else d
            b.box(
                (0.0, y - 0.02 * s, z0 + (d / 2 - depth / 2) * (1 - k)),
                (w, 0.04 * s, depth),
                color,
                mat,
            )
        for sx in (-1.0, 1.0):
            b.box((sx * (w / 2 - 0.015), 0.2 * s, -d / 4), (0.03, 0.4 * s, d / 2), color, mat)
            b.box((sx * (w / 2 - 0.015), 0.1 * s, d / 4), (0.03, 0.2 * s, d / 2), color, mat)
        for y in (0.22 * s, 0.42 * s):
            b.box(
                (0.0, y + 0.001, 0.0 if y < 0.3 * s else -d / 4),
                (w * 0.8, 0.002, 0.04),
                shade(color, 0.6),
                mat,
                faces="+y",
            )
        return ObjectModel(b.build(), [Surface(0.42 * s, (0.0, -d / 4), (w, d / 2))])
    w, d, h = 0.42 * s, 0.32 * s, 0.3 * s
    leg = color_rgb("dark brown")
    for sx in (-1.0, 1.0):
        for sz in (-1.0, 1.0):
            top = (sx * (w / 2 - 0.05), h - 0.08 * s, sz * (d / 2 - 0.05))
            foot = (sx * (w / 2 - 0.02), 0.0, sz * (d / 2 - 0.02))
            beam(b, foot, top, 0.03, 0.03, leg, WOOD)
    b.box((0.0, h - 0.09 * s, 0.0), (w - 0.04, 0.04 * s, d - 0.04), leg, WOOD)
    b.box((0.0, h - 0.045 * s, 0.0), (w, 0.09 * s, d), color, mat)
    b.box((0.0, h - 0.005 * s, 0.0), (w - 0.02, 0.01 * s, d - 0.02), shade(color, 1.1), mat)
    mesh = standing_on_floor(b.build())  # the splayed legs' corners dip below the floor
    return ObjectModel(mesh, [Surface(float(mesh.bounds()[1][1]), (0.0, 0.0), (w, d))])


def _basin(b: MeshBuilder, x: float, top: float, z: float, s: float) -> None:
    """A white basin set into a counter at height ``top``, with a chrome tap behind it."""
    b.cylinder((x, top, z), 0.19 * s, 0.004, WHITE, CERAMIC, segments=12)
    b.cylinder((x, top + 0.002, z), 0.15 * s, 0.003, shade(WHITE, 0.7), CERAMIC, segments=12)
    tap_z = z - 0.22 * s
    b.cylinder((x, top, tap_z), 0.018, 0.2 * s, SILVER, METAL, segments=8)
    b.box((x, top + 0.19 * s, tap_z + 0.06 * s), (0.025, 0.025, 0.12 * s), SILVER, METAL)


def build_vanity(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A bathroom cabinet under a stone top with one or two basins set into it."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    double = style.shape == "double"
    w, d, h = (1.3 if double else 0.8) * s, 0.52 * s, 0.85 * s
    top_rgb, top_mat = (
        worktop_finish(style) if style.material == "wood" else (WHITE, material_index("marble"))
    )
    b = MeshBuilder()
    b.box(
        (0.0, 0.05 * s, -0.03),
        (w - 0.04, 0.1 * s, d - 0.1),
        shade(color, 0.5),
        mat,
        faces="+x-x+z-z",
    )
    z_front = add_carcass(b, w, d, (0.1 * s, h - 0.04), color, mat)
    add_top(b, w + 0.02, d + 0.02, h, 0.04, top_rgb, top_mat)
    xs = (-w / 2, w / 2)
    cols = 4 if double else 2
    add_fronts(b, xs, (h - 0.2 * s, h - 0.045), z_front, (cols // 2, 1), color, mat)
    add_fronts(b, xs, (0.1 * s, h - 0.2 * s), z_front, (cols, 1), color, mat, "door")
    for x in (-w / 4, w / 4) if double else (0.0,):
        _basin(b, x, h, 0.03 * s, s)
    return ObjectModel(b.build(), [Surface(h, (0.0, -d / 2 + 0.06), (w, 0.1))])


def build_countertop(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A thick slab with its back to the wall: a high bar top on two legs, or a top whose
    end turns down to the floor in one piece (waterfall) and rests on a post at the other."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    bar = style.shape == "bar"
    w = float(rng.uniform(1.2, 1.6)) * s
    d, h, t = (0.45 if bar else 0.55) * s, (1.05 if bar else 0.85) * s, 0.05 * s
    b = MeshBuilder()
    add_top(b, w, d, h, t, color, mat)
    b.box(
        (0.0, h - t - 0.001, 0.0), (w - 0.02, 0.002, d - 0.02), shade(color, 0.7), mat, faces="-y"
    )
    if bar:
        for x in (-w / 2 + 0.12, w / 2 - 0.12):
            b.cylinder((x, 0.0, d / 2 - 0.08), 0.025, h - t, SILVER, METAL, segments=8)
            b.cylinder((x, 0.0, d / 2 - 0.08), 0.09, 0.015, SILVER, METAL, segments=10)
        b.box((0.0, 0.3 * s, d / 2 - 0.08), (w - 0.24, 0.025, 0.025), SILVER, METAL)
    else:
        b.box((w / 2 - t / 2, (h - t) / 2, 0.0), (t, h - t, d), color, mat)
        b.box((-w / 2 + 0.06, (h - t) / 2, -d / 2 + 0.06), (0.06, h - t, 0.06), BLACK, METAL)
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_stand(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A plant stand (round top and a lower ring on three splayed legs) or a square display
    pedestal with a plinth and a cap."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "pedestal":
        w, h = 0.32 * s, float(rng.uniform(0.9, 1.05)) * s
        b.box((0.0, 0.04 * s, 0.0), (w + 0.06, 0.08 * s, w + 0.06), shade(color, 0.9), mat)
        b.box((0.0, h / 2, 0.0), (w, h - 0.1 * s, w), color, mat)
        b.box((0.0, h - 0.025 * s, 0.0), (w + 0.06, 0.05 * s, w + 0.06), shade(color, 0.9), mat)
        return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w + 0.06, w + 0.06))])
    r, h = 0.13 * s, float(rng.uniform(0.85, 1.0)) * s  # taller and slimmer than a stool
    b.cylinder((0.0, h - 0.03, 0.0), r, 0.03, color, mat, segments=14)
    ring_y = h * 0.35
    for k in range(3):
        a = 2.0 * math.pi * k / 3
        ca, sa = math.cos(a), math.sin(a)
        beam(
            b,
            (r * 1.25 * ca, 0.0, r * 1.25 * sa),
            (r * 0.75 * ca, h - 0.03, r * 0.75 * sa),
            0.03,
            0.03,
            color,
            mat,
        )
    b.cylinder((0.0, ring_y, 0.0), r * 0.95, 0.02, color, mat, segments=14)
    mesh = standing_on_floor(b.build())
    return ObjectModel(mesh, [Surface(float(mesh.bounds()[1][1]), (0.0, 0.0), (1.4 * r, 1.4 * r))])


def _rails_and_steps(
    b: MeshBuilder,
    foot: tuple[float, float],
    top: tuple[float, float],
    w: float,
    n: int,
    color: Rgb,
    mat: int,
) -> None:
    """Two side rails from ``foot`` to ``top`` ((z, y) pairs) with ``n`` flat steps between."""
    (z0, y0), (z1, y1) = foot, top
    for x in (-w / 2, w / 2):
        beam(b, (x, y0, z0), (x, y1, z1), 0.05, 0.025, color, mat, side=(0.0, 0.0, 1.0))
    for k in range(1, n + 1):
        f = k / (n + 0.6)
        z, y = z0 + (z1 - z0) * f, y0 + (y1 - y0) * f
        b.box((0.0, y, z), (w, 0.025, 0.1), shade(color, 0.9), mat)


def build_ladder(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An opened step ladder (steps in front, a leg frame behind), or a straight ladder
    leaning on the wall."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "step":
        h, spread, w = 1.45 * s, 0.42 * s, 0.45 * s
        _rails_and_steps(b, (spread, 0.0), (0.0, h), w, 4, color, mat)
        for x in (-w / 2, w / 2):
            beam(b, (x, 0.0, -spread), (x, h, -0.03), 0.04, 0.02, color, mat, side=(0.0, 0.0, 1.0))
        b.box((0.0, h + 0.02, -0.01), (w + 0.04, 0.04, 0.16), shade(color, 0.7), PLASTIC)
        return ObjectModel(standing_on_floor(b.build()))
    h, lean, w = 2.1 * s, 0.55 * s, 0.42 * s
    _rails_and_steps(b, (lean / 2, 0.0), (-lean / 2, h), w, 7, color, mat)
    return ObjectModel(standing_on_floor(b.build()))


def build_cart(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A trolley on castors: three wire-edged baskets on corner posts (utility) or two
    glass-topped trays with a push handle (bar)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    bar = style.shape == "bar"
    w, d = (0.75 if bar else 0.45) * s, (0.42 if bar else 0.35) * s
    tiers = (0.25, 0.75) if bar else (0.18, 0.45, 0.72)
    h = tiers[-1] * s
    b = MeshBuilder()
    for sx in (-1.0, 1.0):
        for sz in (-1.0, 1.0):
            x, z = sx * (w / 2 - 0.02), sz * (d / 2 - 0.02)
            b.cylinder((x, 0.06 * s, z), 0.012, h - 0.05 * s, color, mat, segments=6)
            b.cylinder(
                (x - 0.03 * s, 0.035 * s, z), 0.035 * s, 0.06 * s, BLACK, PLASTIC, 8, axis="x"
            )
    for y in tiers:
        top_y = y * s
        tray = (0.72, 0.84, 0.88) if bar else color
        b.box((0.0, top_y - 0.01, 0.0), (w, 0.02, d), tray, material_index("glass") if bar else mat)
        if not bar:
            for sz in (-1.0, 1.0):
                b.box(
                    (0.0, top_y + 0.04, sz * (d / 2 - 0.01)),
                    (w, 0.08, 0.01),
                    color,
                    mat,
                    faces="+z-z+y",
                )
            for sx in (-1.0, 1.0):
                b.box(
                    (sx * (w / 2 - 0.01), top_y + 0.04, 0.0),
                    (0.01, 0.08, d),
                    color,
                    mat,
                    faces="+x-x+y",
                )
    if bar:
        x = w / 2 + 0.05
        b.cylinder((x, h + 0.02, -d / 2 + 0.03), 0.015, d - 0.06, color, mat, segments=6, axis="z")
        for z in (-d / 2 + 0.03, d / 2 - 0.03):
            beam(b, (w / 2 - 0.02, h - 0.02, z), (x, h + 0.02, z), 0.02, 0.02, color, mat)
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w - 0.04, d - 0.04))])


def build_pool_table(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A felt bed inside cushioned wooden rails with six pockets, on legs, with balls and a cue."""
    s = style.scale
    felt, frame_mat = color_rgb(style.color), material_index(style.material)
    wood = color_rgb("dark brown") if style.material == "wood" else color_rgb("black")
    small = style.shape == "compact"
    length, width, h = (2.0 if small else 2.5) * s, (1.1 if small else 1.4) * s, 0.8 * s
    rail = 0.12 * s
    b = MeshBuilder()
    add_legs(b, length - 0.2, width - 0.2, h - 0.15, 0.12 * s, wood, frame_mat)
    b.box((0.0, h - 0.09, 0.0), (length, 0.12, width), wood, frame_mat)
    b.box((0.0, h - 0.02, 0.0), (length - 2 * rail, 0.02, width - 2 * rail), felt, FABRIC)
    for sz in (-1.0, 1.0):
        b.box((0.0, h, sz * (width / 2 - rail / 2)), (length, 0.06, rail), wood, frame_mat)
    for sx in (-1.0, 1.0):
        b.box(
            (sx * (length / 2 - rail / 2), h, 0.0), (rail, 0.06, width - 2 * rail), wood, frame_mat
        )
    for px in (-1.0, 0.0, 1.0):
        for pz in (-1.0, 1.0):
            x = px * (length / 2 - rail * 0.9)
            b.cylinder(
                (x, h + 0.031, pz * (width / 2 - rail * 0.9)), 0.055 * s, 0.001, BLACK, PLASTIC, 8
            )
    ball_colors = ("yellow", "red", "blue", "orange", "purple", "green", "white", "black")
    for k in range(int(rng.integers(4, 8))):
        x = float(rng.uniform(-0.35, 0.35)) * length
        z = float(rng.uniform(-0.3, 0.3)) * width
        b.sphere((x, h - 0.01 + 0.03, z), 0.03, color_rgb(ball_colors[k]), PLASTIC, segments=5)
    beam(
        b,
        (-length * 0.35, h + 0.03, width * 0.25),
        (length * 0.2, h + 0.05, -width * 0.1),
        0.02,
        0.02,
        color_rgb("beige"),
        WOOD,
    )
    return ObjectModel(b.build(), [Surface(h + 0.03, (0.0, 0.0), (length * 0.5, width * 0.5))])


CATEGORIES: list[Category] = [
    Category(
        name="footstool",
        shapes={"padded": "padded footstool", "step": "step stool"},
        colors=("red", "green", "gray", "beige", "blue", "white", "brown"),
        materials=("fabric", "leather", "plastic"),
        placement=Placement.FLOOR,
        rooms={"living room": 0.2, "bedroom": 0.1, "kitchen": 0.1, "bathroom": 0.05},
        build=build_footstool,
    ),
    Category(
        name="vanity",
        shapes={"single": "bathroom vanity", "double": "double vanity"},
        colors=(*PAINT_COLORS, "brown"),
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bathroom": 0.35, "toilet": 0.1},
        build=build_vanity,
    ),
    Category(
        name="countertop",
        shapes={"waterfall": "waterfall countertop", "bar": "bar countertop"},
        colors=("white", "gray", "black", "brown", "beige", "dark gray"),
        materials=("marble", "wood"),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 0.3, "dining room": 0.1, "bathroom": 0.1, "storage room": 0.1},
        build=build_countertop,
    ),
    Category(
        name="stand",
        shapes={"pedestal": "display pedestal", "plant": "plant stand"},
        colors=(*WOOD_COLORS, "gold"),
        materials=("wood", "metal", "marble"),
        placement=Placement.CORNER,
        rooms={"living room": 0.25, "corridor": 0.15, "bedroom": 0.05, "study": 0.05},
        build=build_stand,
    ),
    Category(
        name="ladder",
        shapes={"step": "step ladder", "leaning": "leaning ladder"},
        colors=("silver", "gray", "brown", "orange", "white"),
        materials=("metal", "wood"),
        placement=Placement.AGAINST_WALL,
        rooms={"storage room": 0.35, "corridor": 0.04, "gym": 0.03},
        build=build_ladder,
    ),
    Category(
        name="cart",
        shapes={"utility": "utility cart", "bar": "bar cart"},
        colors=("silver", "black", "white", "gold", "teal", "gray"),
        materials=("metal",),
        placement=Placement.AGAINST_WALL,
        rooms={
            "kitchen": 0.15,
            "dining room": 0.1,
            "bathroom": 0.05,
            "storage room": 0.1,
            "study": 0.05,
        },
        build=build_cart,
    ),
    Category(
        name="pool table",
        shapes={"full-size": "pool table", "compact": "compact pool table"},
        colors=("green", "blue", "red", "navy"),
        materials=("wood", "metal"),
        placement=Placement.FLOOR,
        rooms={"gym": 0.12, "living room": 0.03, "storage room": 0.02},
        build=build_pool_table,
    ),
]
