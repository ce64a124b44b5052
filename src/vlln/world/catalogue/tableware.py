"""Small things on tables and shelves: cups, bowls, plates, bottles, books, teapots, fruit.

Every model here is meant to stand on a surface, so each fits a 0.4 x 0.3 m footprint even at
the largest scale and stays under ~150 triangles.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

DISH_COLORS = ("white", "cream", "blue", "red", "green", "yellow", "black", "gray")
BOOK_COLORS = (
    "red",
    "blue",
    "green",
    "navy",
    "black",
    "brown",
    "yellow",
    "white",
    "purple",
    "orange",
    "dark green",
    "teal",
)
PAPER = color_rgb("cream")
GILT = color_rgb("gold")  # bands on book spines
PLAIN = material_index("plain")


def _hollow(
    b: MeshBuilder, r0: float, r1: float, h: float, color: Rgb, material: int, y: float = 0.0
) -> None:
    """A frustum whose top reads as an open, shadowed inside (a cup, a bowl)."""
    b.cylinder((0.0, y, 0.0), r0, h, color, material, segments=8, radius_top=r1)
    b.cylinder((0.0, y + h, 0.0), r1 * 0.88, 0.001, shade(color, 0.7), material, segments=8)


def _handle(b: MeshBuilder, x: float, y: float, size: float, color: Rgb, material: int) -> None:
    """A loop handle on the +x side of a vessel whose wall is at ``x``."""
    ring(
        b,
        (x, y, 0.0),
        size,
        size * 0.3,
        size * 0.35,
        color,
        material,
        segments=6,
        arc=(-math.pi / 2, math.pi / 2),
    )


def build_cup(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A mug with a handle, a teacup on a saucer, or a plain drinking glass."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "teacup":
        saucer, h = 0.012 * s, 0.05 * s
        b.cylinder((0.0, 0.0, 0.0), 0.05 * s, saucer, color, mat, segments=8, radius_top=0.07 * s)
        _hollow(b, 0.03 * s, 0.045 * s, h, color, mat, y=saucer)
        _handle(b, 0.038 * s, saucer + h * 0.55, 0.02 * s, color, mat)
        return ObjectModel(b.build())
    if style.shape == "glass":
        h = float(rng.uniform(0.09, 0.13)) * s
        _hollow(b, 0.03 * s, 0.037 * s, h, color, material_index("glass"))
        return ObjectModel(b.build())
    h, r = float(rng.uniform(0.085, 0.105)) * s, 0.04 * s
    _hollow(b, r, r, h, color, mat)
    _handle(b, r, h * 0.5, h * 0.32, color, mat)
    return ObjectModel(b.build())


def build_bowl(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A round bowl, deep for cereal or shallow for salad."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    deep = style.shape == "deep"
    r = (0.065 if deep else 0.09) * s * float(rng.uniform(0.9, 1.1))
    b = MeshBuilder()
    _hollow(b, r * 0.55, r, (0.07 if deep else 0.045) * s, color, mat)
    return ObjectModel(b.build())


def build_plate(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A flat plate with a raised rim: a dinner plate, a side plate or a stack of them."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    r = (0.1 if style.shape == "side" else 0.125) * s
    count = int(rng.integers(3, 6)) if style.shape == "stack" else 1
    t = 0.018 * s
    b = MeshBuilder()
    for k in range(count):
        b.cylinder((0.0, k * t, 0.0), r * 0.7, t, color, mat, segments=8, radius_top=r)
    b.cylinder((0.0, count * t, 0.0), r * 0.7, 0.001, shade(color, 0.92), mat, segments=8)
    return ObjectModel(b.build())


def build_bottle(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A body, a shoulder, a neck and a cap: a labelled wine bottle or a water bottle."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    wine = style.shape == "wine"
    r = (0.037 if wine else 0.033) * s
    body = float(rng.uniform(0.17, 0.21) if wine else rng.uniform(0.14, 0.18)) * s
    shoulder, neck = (0.05 if wine else 0.03) * s, (0.08 if wine else 0.02) * s
    b = MeshBuilder()
    b.cylinder((0.0, 0.0, 0.0), r, body, color, mat, segments=8)
    b.cylinder((0.0, body, 0.0), r, shoulder, color, mat, segments=8, radius_top=0.013 * s)
    b.cylinder((0.0, body + shoulder, 0.0), 0.013 * s, neck, color, mat, segments=6)
    top = body + shoulder + neck
    cap = color_rgb("dark brown" if wine else "blue")
    b.cylinder((0.0, top, 0.0), 0.015 * s, 0.02 * s, cap, material_index("plastic"), segments=6)
    if wine:
        b.cylinder(
            (0.0, body * 0.3, 0.0),
            r + 0.001,
            body * 0.4,
            color_rgb("cream"),
            PLAIN,
            segments=8,
            caps=False,
        )
    return ObjectModel(b.build())


def _book(
    b: MeshBuilder,
    center: tuple[float, float, float],
    size: tuple[float, float, float],
    color: Rgb,
    cover: int,
    standing: bool,
) -> None:
    """Two boards and a spine around a cream page block showing on the open edges.

    Standing books have their spine facing +z (out of a shelf); lying ones face up.
    """
    cx, cy, cz = center
    w, h, d = size  # thickness, height, depth for a standing book
    board = 0.003
    if standing:
        b.box((cx, cy, cz - 0.003), (w - 2 * board, h - 0.006, d - 0.006), PAPER, PLAIN)
        for x in (-1, 1):
            b.box((cx + x * (w - board) / 2, cy, cz), (board, h, d), color, cover)
        b.box((cx, cy, cz + d / 2 - board / 2), (w, h, board), color, cover)
        for y in (cy + h * 0.32, cy - h * 0.32):  # gilt bands across the spine
            b.box((cx, y, cz + d / 2 + 0.0005), (w, 0.006, 0.001), GILT, PLAIN, faces="+z")
    else:
        b.box((cx - 0.003, cy, cz), (h - 0.006, w - 2 * board, d - 0.006), PAPER, PLAIN)
        for y in (-1, 1):
            b.box((cx, cy + y * (w - board) / 2, cz), (h, board, d), color, cover)
        b.box((cx + h / 2 - board / 2, cy, cz), (board, w, d), color, cover)
        for z in (cz + d * 0.32, cz - d * 0.32):
            b.box((cx + h / 2 + 0.0005, cy, z), (0.001, w, 0.006), GILT, PLAIN, faces="+x")


def build_book(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A hardback standing upright, lying flat, or a small stack topped by this colour."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    w = float(rng.uniform(0.02, 0.045)) * s
    h, d = float(rng.uniform(0.2, 0.25)) * s, float(rng.uniform(0.14, 0.17)) * s
    if style.shape == "standing":
        _book(b, (0.0, h / 2, 0.0), (w, h, d), color, mat, True)
    elif style.shape == "lying":
        _book(b, (0.0, w / 2, 0.0), (w, h, d), color, mat, False)
    else:
        y = 0.0
        count = int(rng.integers(2, 4))
        for k in range(count + 1):
            top = k == count
            t = w if top else float(rng.uniform(0.02, 0.045)) * s
            c = color if top else color_rgb(BOOK_COLORS[int(rng.integers(len(BOOK_COLORS)))])
            hk, dk = (h, d) if top else (h * float(rng.uniform(0.9, 1.1)), d)
            _book(b, (float(rng.uniform(-0.01, 0.01)), y + t / 2, 0.0), (t, hk, dk), c, mat, False)
            y += t
    return ObjectModel(b.build())


def build_teapot(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A round pot with a lid and knob, a spout on one side and a loop handle on the other."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    r = float(rng.uniform(0.07, 0.085)) * s
    hb = r * 0.8
    b = MeshBuilder()
    b.sphere((0.0, hb, 0.0), r, color, mat, segments=8, scale=(1.0, 0.8, 1.0))
    b.cylinder((0.0, hb * 1.7, 0.0), r * 0.5, 0.015 * s, color, mat, segments=8, radius_top=r * 0.3)
    b.cylinder((0.0, hb * 1.7 + 0.015 * s, 0.0), 0.01 * s, 0.015 * s, color, mat, segments=6)
    beam(
        b,
        (r * 0.8, hb * 0.8, 0.0),
        (r * 1.55, hb * 1.6, 0.0),
        0.018 * s,
        0.018 * s,
        color,
        mat,
        side=(0.0, 0.0, 1.0),
    )
    ring(
        b,
        (-r * 0.85, hb * 1.05, 0.0),
        r * 0.55,
        0.012 * s,
        0.015 * s,
        color,
        mat,
        segments=6,
        arc=(math.pi / 2, 3 * math.pi / 2),
    )
    return ObjectModel(b.build())


def build_fruit_bowl(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wide shallow bowl heaped with apples, oranges and lemons."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    r, h = 0.12 * s, 0.06 * s
    b = MeshBuilder()
    _hollow(b, r * 0.5, r, h, color, mat)
    fruit = ("red", "orange", "yellow", "green")
    n = int(rng.integers(4, 7))
    for k in range(n):
        a = 2 * math.pi * k / n + float(rng.uniform(-0.2, 0.2))
        d = (0.0 if k == 0 else 0.055) * s
        fr = float(rng.uniform(0.03, 0.038)) * s
        y = h + (0.04 * s if k == 0 else 0.01 * s)
        b.sphere(
            (d * math.cos(a), y, d * math.sin(a)),
            fr,
            color_rgb(fruit[int(rng.integers(4))]),
            PLAIN,
            segments=5,
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="cup",
        shapes={"mug": "mug", "teacup": "teacup", "glass": "drinking glass"},
        colors=DISH_COLORS,
        materials=("ceramic", "plastic", "glass"),
        placement=Placement.ON_SURFACE,
        rooms={
            "kitchen": 1.5,
            "dining room": 1.5,
            "living room": 0.8,
            "study": 0.6,
            "bedroom": 0.3,
        },
        build=build_cup,
    ),
    Category(
        name="bowl",
        shapes={"deep": "cereal bowl", "shallow": "salad bowl"},
        colors=DISH_COLORS,
        materials=("ceramic", "glass", "wood", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 1.0, "dining room": 0.8, "living room": 0.1},
        build=build_bowl,
    ),
    Category(
        name="plate",
        shapes={"dinner": "dinner plate", "side": "side plate", "stack": "stack of plates"},
        colors=DISH_COLORS,
        materials=("ceramic", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.8, "dining room": 1.5},
        build=build_plate,
    ),
    Category(
        name="bottle",
        shapes={"wine": "wine bottle", "water": "water bottle"},
        colors=("green", "dark green", "brown", "light blue", "white", "red"),
        materials=("glass", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={
            "kitchen": 1.2,
            "dining room": 1.0,
            "living room": 0.5,
            "bathroom": 0.5,
            "bedroom": 0.2,
            "study": 0.2,
            "gym": 0.5,
        },
        build=build_bottle,
    ),
    Category(
        name="book",
        shapes={"standing": "book", "lying": "book lying flat", "stack": "stack of books"},
        colors=BOOK_COLORS,
        materials=("leather", "fabric", "plain"),
        placement=Placement.ON_SURFACE,
        rooms={
            "living room": 2.0,
            "bedroom": 1.5,
            "study": 3.0,
            "dining room": 0.2,
            "corridor": 0.2,
        },
        build=build_book,
    ),
    Category(
        name="teapot",
        shapes={"round": "teapot"},
        colors=("white", "blue", "red", "green", "cream", "black", "brown"),
        materials=("ceramic", "metal", "glass"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.3, "dining room": 0.3, "living room": 0.1},
        build=build_teapot,
    ),
    Category(
        name="fruit bowl",
        shapes={"round": "bowl of fruit"},
        colors=("white", "brown", "silver", "black", "green", "blue"),
        materials=("ceramic", "wood", "glass", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.4, "dining room": 0.5, "living room": 0.15},
        build=build_fruit_bowl,
    ),
]
