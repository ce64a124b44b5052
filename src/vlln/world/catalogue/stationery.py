"""Paper and desk things: notebooks, magazines, photo albums and adhesive tape.

Every model lies on a desk, a table or a shelf and fits a 0.4 x 0.3 m footprint at the
largest scale.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

PLAIN = material_index("plain")
PLASTIC = material_index("plastic")
METAL = material_index("metal")
PAGE = color_rgb("white")
LINE = color_rgb("light blue")
SILVER = color_rgb("silver")
PHOTO_COLORS = ("blue", "green", "orange", "light blue", "yellow", "red", "teal", "pink")


def _pages(b: MeshBuilder, x: float, w: float, d: float, top: float, lines: int) -> None:
    """A white page block up to height ``top`` with ruled lines across it."""
    b.box((x, top / 2, 0.0), (w, top, d), PAGE, PLAIN)
    for k in range(lines):
        z = -d / 2 + d * (k + 1.5) / (lines + 2)
        b.box((x, top + 0.0004, z), (w * 0.85, 0.0008, 0.0015), LINE, PLAIN, faces="+y")


def build_notebook(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A closed spiral notebook with its coil along one edge, or one lying open with a pen."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.14 * s, 0.2 * s
    b = MeshBuilder()
    if style.shape == "open":
        t = 0.006 * s
        b.box((0.0, 0.001 * s, 0.0), (2 * w + 0.01 * s, 0.002 * s, d + 0.006 * s), color, mat)
        for side in (-1, 1):
            _pages(b, side * (w / 2 + 0.002 * s), w, d, t, 9)
        pen = color_rgb("navy" if style.color != "navy" else "black")
        slant = float(rng.uniform(-0.04, 0.04)) * s
        beam(
            b,
            (w * 0.3 - slant, t + 0.004 * s, -d * 0.3),
            (w * 0.3 + slant, t + 0.004 * s, d * 0.3),
            0.008 * s,
            0.008 * s,
            pen,
            PLASTIC,
        )
        return ObjectModel(b.build())
    t = float(rng.uniform(0.008, 0.014)) * s
    cover = 0.002 * s
    b.box((0.0, cover / 2, 0.0), (w, cover, d), color, mat)
    b.box((0.0, cover + t / 2, 0.0), (w * 0.98, t, d * 0.98), PAGE, PLAIN)
    b.box((0.0, cover * 1.5 + t, 0.0), (w, cover, d), color, mat)
    b.box((w * 0.08, cover * 2 + t + 0.0005, -d * 0.25), (w * 0.5, 0.001, 0.03 * s), PAGE, PLAIN)
    radius = (t + 2 * cover) / 2
    for k in range(8):
        z = -d / 2 + d * (k + 0.5) / 8
        ring(
            b,
            (-w / 2, radius, z),
            radius,
            0.0015,
            0.003,
            SILVER,
            METAL,
            axis="z",
            segments=6,
            arc=(math.pi / 2, 3 * math.pi / 2),
        )
    return ObjectModel(b.build())


def _cover(
    b: MeshBuilder, w: float, d: float, base: float, t: float, color: Rgb, mat: int, photo: Rgb
) -> None:
    """A magazine of thickness ``t`` lying at height ``base``: a title band over a big photo."""
    top = base + t
    b.box((0.0, base + t / 2, 0.0), (w, t, d), PAGE, PLAIN)
    b.box((0.0, top + 0.0005, 0.0), (w, 0.001, d), color, mat, faces="+y")
    b.box((0.0, top + 0.0011, d * 0.08), (w * 0.86, 0.0004, d * 0.7), photo, PLAIN, faces="+y")
    b.box((0.0, top + 0.0011, -d * 0.39), (w * 0.8, 0.0004, d * 0.12), PAGE, PLAIN, faces="+y")


def build_magazine(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A single magazine lying flat, or a loose stack of them with this one on top."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, t = 0.19 * s, 0.24 * s, 0.005 * s
    b = MeshBuilder()
    below = int(rng.integers(2, 5)) if style.shape == "stack" else 0
    for k in range(below):
        tint = color_rgb(PHOTO_COLORS[int(rng.integers(len(PHOTO_COLORS)))])
        yaw = float(rng.uniform(-0.06, 0.06))
        b.box((0.0, (k + 0.5) * t, 0.0), (w * 0.96, t, d * 0.96), tint, mat, yaw=yaw)
    photo = color_rgb(PHOTO_COLORS[int(rng.integers(len(PHOTO_COLORS)))])
    _cover(b, w, d, below * t, t, color, mat, photo)
    return ObjectModel(b.build())


def build_album(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A thick padded photo album with a photo in its cover window, or a ribbon-tied scrapbook."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.25 * s, float(rng.uniform(0.22, 0.25)) * s
    t = 0.05 * s
    b = MeshBuilder()
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    b.box((0.005 * s, t / 2, 0.0), (w, t * 0.7, d * 0.96), color_rgb("cream"), PLAIN)
    b.box(
        (-w / 2 + 0.012 * s, t * 0.52, 0.0),
        (0.024 * s, t * 1.04, d * 1.01),
        shade(color, 0.75),
        mat,
    )
    if style.shape == "photo":
        b.box(
            (0.02 * s, t + 0.0005, 0.0),
            (w * 0.5, 0.001, d * 0.45),
            color_rgb("cream"),
            PLAIN,
            faces="+y",
        )
        photo = color_rgb(PHOTO_COLORS[int(rng.integers(len(PHOTO_COLORS)))])
        b.box((0.02 * s, t + 0.0012, 0.0), (w * 0.4, 0.0004, d * 0.35), photo, PLAIN, faces="+y")
    else:
        ribbon = color_rgb("red" if style.color != "red" else "gold")
        b.box(
            (0.0, t * 0.52, 0.0), (w * 1.01, t * 1.04, 0.015 * s), ribbon, material_index("fabric")
        )
        b.sphere(
            (w * 0.25, t, 0.0),
            1.0,
            ribbon,
            material_index("fabric"),
            segments=6,
            scale=(0.02 * s, 0.008 * s, 0.015 * s),
        )
    return ObjectModel(b.build())


def build_adhesive_tape(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A roll of tape lying on its side, or a weighted dispenser holding a roll upright."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    core = color_rgb("beige")
    b = MeshBuilder()
    if style.shape == "roll":
        r, width = float(rng.uniform(0.045, 0.055)) * s, 0.048 * s
        ring(b, (0.0, width / 2, 0.0), r, r * 0.35, width, color, mat, axis="y", segments=14)
        ring(
            b, (0.0, width / 2, 0.0), r * 0.65, 0.005 * s, width, core, PLAIN, axis="y", segments=14
        )
        return ObjectModel(b.build())
    base = color_rgb("black" if style.color != "black" else "dark gray")
    w, d, h = 0.07 * s, 0.15 * s, 0.045 * s
    b.box((0.0, h / 2, 0.0), (w, h, d), base, PLASTIC)
    b.box((0.0, h * 1.3, d * 0.38), (w * 0.9, h * 0.6, 0.03 * s), base, PLASTIC)
    r = 0.04 * s
    ring(
        b,
        (0.0, h + r * 0.9, -d * 0.12),
        r * 1.15,
        r * 0.35,
        0.02 * s,
        color,
        mat,
        axis="x",
        segments=12,
    )
    b.box((0.0, h * 1.62, d * 0.42), (w * 0.85, 0.003 * s, 0.012 * s), SILVER, METAL)
    beam(
        b,
        (0.0, h + r * 2.05, -d * 0.12),
        (0.0, h * 1.6, d * 0.4),
        0.019 * s,
        0.001,
        color,
        mat,
        side=(1.0, 0.0, 0.0),
    )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="notebook",
        shapes={"spiral": "spiral notebook", "open": "open notebook"},
        colors=("red", "blue", "black", "green", "yellow", "purple", "orange", "navy", "pink"),
        materials=("plain", "plastic", "leather"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.5, "bedroom": 0.2, "living room": 0.08},
        build=build_notebook,
    ),
    Category(
        name="magazine",
        shapes={"single": "single magazine", "stack": "stack of magazines"},
        colors=("red", "blue", "white", "black", "yellow", "green", "orange", "pink"),
        materials=("plain",),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.4, "bedroom": 0.15, "toilet": 0.1, "study": 0.1},
        build=build_magazine,
    ),
    Category(
        name="album",
        shapes={"photo": "photo album", "scrapbook": "scrapbook"},
        colors=("brown", "black", "red", "navy", "beige", "dark green", "white", "pink"),
        materials=("leather", "fabric"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.15, "study": 0.1, "bedroom": 0.08},
        build=build_album,
    ),
    Category(
        name="adhesive tape",
        shapes={"roll": "roll of tape", "dispenser": "tape dispenser"},
        colors=("beige", "brown", "light gray", "white", "red", "blue", "yellow"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.2, "storage room": 0.2, "kitchen": 0.05},
        build=build_adhesive_tape,
    ),
]
