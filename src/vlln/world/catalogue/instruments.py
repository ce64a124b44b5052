"""Musical instruments: pianos and guitars.

A piano is recognised by its keys, so the keyboard is drawn key by key: white key tops with
gaps that show the dark key bed, and raised black keys in the 2 + 3 pattern of each octave.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.parts import beam, rotated_about_x, shade, standing_on_floor
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder

BLACK = color_rgb("black")
WHITE = color_rgb("white")
PLAIN = material_index("plain")
METAL = material_index("metal")
BLACK_KEY_AFTER = (0, 1, 3, 4, 5)  # white keys (C=0) followed by a black key in an octave


def _keys(b: MeshBuilder, width: float, y: float, z_back: float, depth: float) -> None:
    """A keyboard centred on x = 0: white key tops at height ``y`` from ``z_back`` forwards."""
    n_white = max(14, int(width / 0.03))  # keys a little wide: fewer triangles
    pitch = width / n_white
    b.box((0.0, y - 0.01, z_back + depth / 2), (width, 0.02, depth), BLACK, PLAIN, faces="+y+z")
    for k in range(n_white):
        x = -width / 2 + pitch * (k + 0.5)
        b.box(
            (x, y + 0.0005, z_back + depth / 2), (pitch * 0.9, 0.0, depth), WHITE, PLAIN, faces="+y"
        )
        if k % 7 in BLACK_KEY_AFTER and k < n_white - 1:
            b.box(
                (x + pitch / 2, y + 0.009, z_back + depth * 0.32),
                (pitch * 0.55, 0.018, depth * 0.62),
                BLACK,
                PLAIN,
                faces="+y+z",
            )


def build_piano(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An upright piano against the wall, or a grand piano with a closed lid on three legs."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    gold = color_rgb("gold")
    key_y, key_d = 0.72 * s, 0.15 * s
    b = MeshBuilder()
    if style.shape == "grand":
        w, d = 1.45 * s, float(rng.uniform(1.5, 1.8)) * s
        case_y, case_h = 0.62 * s, 0.3 * s
        front = d / 2
        b.box((0.0, case_y + case_h / 2, front - 0.45 * d), (w, case_h, 0.9 * d), color, mat)
        b.box(
            (-w * 0.2, case_y + case_h / 2, -d / 2 + 0.05 * d),
            (w * 0.6, case_h, 0.1 * d),
            color,
            mat,
        )
        for lx, lz in (
            (-w * 0.42, front - 0.15 * s),
            (w * 0.42, front - 0.15 * s),
            (-w * 0.2, -d / 2 + 0.15 * s),
        ):
            b.box((lx, case_y / 2, lz), (0.08 * s, case_y, 0.08 * s), color, mat)
        b.box((0.0, case_y * 0.5, front - 0.1 * s), (0.12 * s, case_y, 0.04 * s), color, mat)
        beam(
            b,
            (0.0, case_y + case_h, front - 0.22 * s),
            (0.0, case_y + case_h + 0.25 * s, front - 0.3 * s),
            w * 0.5,
            0.015 * s,
            color,
            mat,
        )
        _keys(b, w * 0.88, key_y + 0.02 * s, front, key_d)
        b.box((0.0, key_y - 0.05 * s, front + key_d / 2), (w * 0.95, 0.1 * s, key_d), color, mat)
        for k in (-1, 0, 1):
            b.box(
                (k * 0.05 * s, 0.03 * s, front - 0.08 * s),
                (0.025 * s, 0.012, 0.06 * s),
                gold,
                METAL,
            )
        return ObjectModel(b.build())
    w, h = 1.45 * s, float(rng.uniform(1.1, 1.3)) * s
    back_d, d = 0.33 * s, 0.6 * s
    z_keys = -d / 2 + back_d
    b.box((0.0, h / 2, -d / 2 + back_d / 2), (w, h, back_d), color, mat)
    cheek = 0.06 * s
    for x in (-1, 1):
        b.box(
            (x * (w - cheek) / 2, key_y / 2 + 0.05 * s, z_keys + key_d / 2),
            (cheek, key_y + 0.1 * s, key_d + 0.02 * s),
            color,
            mat,
        )
        b.box(
            (x * (w / 2 - 0.1 * s), key_y / 2, d / 2 - 0.1 * s),
            (0.06 * s, key_y, 0.06 * s),
            color,
            mat,
        )
    b.box((0.0, key_y - 0.06 * s, z_keys + key_d / 2), (w - 2 * cheek, 0.1 * s, key_d), color, mat)
    _keys(b, w - 2 * cheek, key_y, z_keys, key_d)
    b.box(
        (0.0, key_y + 0.18 * s, z_keys + 0.02 * s),
        (w * 0.7, 0.2 * s, 0.02 * s),
        shade(color, 0.85),
        mat,
    )
    for k in (-1, 0, 1):
        b.box((k * 0.05 * s, 0.03 * s, z_keys + 0.01), (0.025 * s, 0.012, 0.06 * s), gold, METAL)
    return ObjectModel(b.build(), [Surface(h, (0.0, -d / 2 + back_d / 2), (w, back_d))])


def _guitar_body(style: Style) -> Mesh:
    """A guitar standing upright on its bottom edge, strings facing +z."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    electric = style.shape == "electric"
    low, up = (0.16, 0.12) if electric else (0.19, 0.145)
    t = (0.045 if electric else 0.1) * s
    low_y, up_y = low * s, (low + up * 1.25) * s
    neck_c = shade(color, 0.5) if style.color not in ("black", "dark brown") else BLACK
    b = MeshBuilder()
    for y, r in ((low_y, low * s), (up_y, up * s)):
        b.cylinder((0.0, y, -t / 2), r, t, color, mat, segments=12, axis="z")
    top_y = up_y + up * s * 0.9
    b.box(
        (0.0, top_y + 0.22 * s, 0.0), (0.05 * s, 0.5 * s, 0.03 * s), neck_c, material_index("wood")
    )
    b.box(
        (0.0, top_y + 0.55 * s, -0.005),
        (0.08 * s, 0.17 * s, 0.02 * s),
        neck_c,
        material_index("wood"),
    )
    b.box((0.0, low_y * 0.6, t / 2 + 0.004), (0.12 * s, 0.015 * s, 0.008), BLACK, PLAIN)
    if electric:
        guard = WHITE if style.color != "white" else BLACK
        b.box(
            (0.03 * s, low_y + 0.03 * s, t / 2 + 0.002), (0.14 * s, 0.18 * s, 0.004), guard, PLAIN
        )
        for y in (0.8, 1.2):
            b.box((0.0, low_y * y, t / 2 + 0.005), (0.07 * s, 0.02 * s, 0.006), BLACK, PLAIN)
    else:
        b.cylinder(
            (0.0, (low_y + up_y) / 2 + 0.02 * s, t / 2),
            0.045 * s,
            0.002,
            BLACK,
            PLAIN,
            segments=10,
            axis="z",
        )
    for x in (-0.01, 0.0, 0.01):  # strings over the neck and body
        b.box(
            (x * s, (low_y * 0.6 + top_y + 0.47 * s) / 2, t / 2 + 0.01),
            (0.002, top_y + 0.47 * s - low_y * 0.6, 0.002),
            color_rgb("silver"),
            METAL,
            faces="+z",
        )
    return b.build()


def build_guitar(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An acoustic or electric guitar leaning back on a small floor stand."""
    s = style.scale
    lean = math.radians(float(rng.uniform(10.0, 16.0)))
    guitar = rotated_about_x(_guitar_body(style), lean)
    guitar.positions[:, 1] += 0.06 * s
    stand = MeshBuilder()
    black = color_rgb("black")
    for x in (-1, 1):
        beam(
            stand,
            (x * 0.12 * s, 0.01 * s, 0.15 * s),
            (x * 0.06 * s, 0.08 * s, 0.0),
            0.02 * s,
            0.02 * s,
            black,
            METAL,
        )
        beam(
            stand,
            (x * 0.12 * s, 0.01 * s, -0.18 * s),
            (0.0, 0.55 * s, -0.15 * s),
            0.02 * s,
            0.02 * s,
            black,
            METAL,
        )
    stand.box((0.0, 0.07 * s, 0.04 * s), (0.3 * s, 0.03 * s, 0.06 * s), black, METAL)
    return ObjectModel(standing_on_floor(Mesh.concatenate([guitar, stand.build()])))


CATEGORIES: list[Category] = [
    Category(
        name="piano",
        shapes={"upright": "upright piano", "grand": "grand piano"},
        colors=("black", "dark brown", "brown", "white"),
        materials=("wood",),
        placement=Placement.AGAINST_WALL,
        rooms={"living room": 0.08, "study": 0.04},
        build=build_piano,
    ),
    Category(
        name="guitar",
        shapes={"acoustic": "acoustic guitar", "electric": "electric guitar"},
        colors=("brown", "beige", "dark brown", "black", "red", "white", "blue"),
        materials=("wood",),
        placement=Placement.AGAINST_WALL,
        rooms={"living room": 0.08, "bedroom": 0.1, "study": 0.05},
        build=build_guitar,
    ),
]
