"""Things people wear or carry: shoes, hats, caps, gloves and purses.

Shoes stand on the floor by a wall, as they are left in a hall; the rest lie on tables,
dressers and shelves and fit a 0.4 x 0.3 m footprint at the largest scale.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, facing_polygon, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

WEAR_COLORS = ("black", "brown", "white", "red", "blue", "navy", "gray", "beige", "pink", "green")
DARK = color_rgb("black")
GOLD = color_rgb("gold")
PLAIN = material_index("plain")
METAL = material_index("metal")
PLASTIC = material_index("plastic")


def _shoe(b: MeshBuilder, x: float, z: float, shape: str, s: float, color: Rgb, mat: int) -> None:
    """One shoe along z with the toe at +z: a sneaker, a boot or a high-heeled shoe."""
    length, width = 0.26 * s, 0.09 * s
    sole_color = color_rgb("white") if shape == "sneakers" else color_rgb("dark brown")
    if shape == "heels":
        heel = 0.075 * s
        b.box((x, heel / 2, z - length * 0.42), (0.022 * s, heel, 0.022 * s), sole_color, PLASTIC)
        b.box(
            (x, 0.005 * s, z + length * 0.28),
            (width * 0.8, 0.01 * s, length * 0.42),
            sole_color,
            PLASTIC,
        )
        beam(
            b,
            (x, heel + 0.004 * s, z - length * 0.45),
            (x, 0.014 * s, z + length * 0.1),
            width * 0.75,
            0.008 * s,
            color,
            mat,
        )
        b.sphere(
            (x, 0.01 * s, z + length * 0.28),
            1.0,
            color,
            mat,
            segments=8,
            scale=(width * 0.42, 0.03 * s, length * 0.22),
            upper_half_only=True,
        )
        back = (x, heel + 0.015 * s, z - length * 0.38)
        ring(
            b,
            back,
            width * 0.42,
            0.005 * s,
            0.035 * s,
            color,
            mat,
            axis="y",
            segments=6,
            arc=(math.pi, 2 * math.pi),
        )
        return
    sole = 0.025 * s
    b.box((x, sole / 2, z), (width, sole, length), sole_color, PLASTIC)
    rear = 0.2 * s if shape == "boots" else 0.075 * s
    b.box((x, sole + rear / 2, z - length * 0.28), (width * 0.96, rear, length * 0.44), color, mat)
    toe, instep = (x, sole + 0.008 * s, z + length * 0.4), (x, sole + 0.05 * s, z - length * 0.08)
    beam(b, toe, instep, width * 0.94, 0.04 * s, color, mat)
    b.sphere(
        (x, sole, z + length * 0.38),
        1.0,
        color,
        mat,
        segments=10,
        scale=(width * 0.47, 0.028 * s, length * 0.11),
        upper_half_only=True,
    )
    b.box(
        (x, sole + rear + 0.001, z - length * 0.3),
        (width * 0.6, 0.002, length * 0.3),
        DARK,
        PLAIN,
        faces="+y",
    )
    if shape == "sneakers":  # laces across the top of the sloping vamp
        for along in (0.35, 0.55, 0.75):
            y = toe[1] + (instep[1] - toe[1]) * along + 0.021 * s
            z_lace = toe[2] + (instep[2] - toe[2]) * along
            b.box((x, y, z_lace), (width * 0.55, 0.004 * s, 0.008 * s), color_rgb("white"), PLAIN)


def build_shoe(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pair of shoes side by side, one a little ahead of the other."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    ahead = float(rng.uniform(0.0, 0.04)) * s
    _shoe(b, -0.06 * s, 0.0, style.shape, s, color, mat)
    _shoe(b, 0.06 * s, ahead, style.shape, s, color, mat)
    return ObjectModel(b.build())


def build_hat(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wide-brimmed sun hat, a dented fedora, or a knitted beanie with a pompom."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    band = color_rgb("black" if style.color != "black" else "red")
    b = MeshBuilder()
    if style.shape == "beanie":
        r = 0.095 * s
        b.cylinder((0.0, 0.0, 0.0), r * 1.02, 0.04 * s, shade(color, 0.85), mat, segments=10)
        b.sphere(
            (0.0, 0.04 * s, 0.0),
            1.0,
            color,
            mat,
            segments=10,
            scale=(r, 0.12 * s, r),
            upper_half_only=True,
        )
        b.sphere((0.0, 0.17 * s, 0.0), 0.022 * s, shade(color, 1.2), mat, segments=6)
        return ObjectModel(b.build())
    sun = style.shape == "sun"
    brim = (0.125 if sun else 0.11) * s * float(rng.uniform(0.95, 1.05))
    crown_r, crown_h = (0.075 if sun else 0.07) * s, (0.08 if sun else 0.075) * s
    b.sphere(
        (0.0, 0.006 * s, 0.0),
        1.0,
        color,
        mat,
        segments=12,
        scale=(brim, 0.006 * s, brim * (1.0 if sun else 0.85)),
    )
    top = crown_r * (0.85 if sun else 0.7)
    b.cylinder((0.0, 0.0, 0.0), crown_r, crown_h, color, mat, segments=10, radius_top=top)
    if not sun:  # the pinched crease along the crown
        b.box((0.0, crown_h, 0.0), (top * 0.35, 0.012 * s, top * 1.5), shade(color, 0.7), mat)
    b.cylinder(
        (0.0, 0.006 * s, 0.0), crown_r * 1.02, 0.022 * s, band, PLAIN, segments=10, caps=False
    )
    return ObjectModel(b.build())


def build_cap(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A baseball cap with a button and a curved peak, or a flat cap sloping to its peak."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    r = 0.09 * s
    if style.shape == "flat":
        b.sphere(
            (0.0, 0.0, -0.01 * s),
            1.0,
            color,
            mat,
            segments=10,
            scale=(r, 0.06 * s, r * 1.2),
            upper_half_only=True,
        )
        b.sphere(
            (0.0, 0.0, r * 0.9),
            1.0,
            shade(color, 0.9),
            mat,
            segments=8,
            scale=(r * 0.85, 0.012 * s, 0.05 * s),
            upper_half_only=True,
        )
        return ObjectModel(b.build())
    b.sphere(
        (0.0, 0.0, 0.0),
        1.0,
        color,
        mat,
        segments=10,
        scale=(r, 0.09 * s * float(rng.uniform(0.9, 1.1)), r),
        upper_half_only=True,
    )
    b.sphere((0.0, 0.087 * s, 0.0), 0.008 * s, shade(color, 0.7), mat, segments=6)
    peak = shade(color, 0.8)
    beam(b, (0.0, 0.012 * s, r * 0.8), (0.0, 0.004 * s, r * 1.75), r * 1.4, 0.006 * s, peak, mat)
    return ObjectModel(b.build())


def build_glove(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A glove lying flat: five fingers (winter, rubber) or a padded oven mitt with a thumb."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    t = 0.025 * s
    palm_w, palm_l = 0.095 * s, 0.1 * s
    cuff_l = (0.08 if style.shape == "rubber" else 0.05) * s
    b.box((0.0, t / 2, 0.0), (palm_w, t, palm_l), color, mat)
    b.box(
        (0.0, t * 0.45, -palm_l / 2 - cuff_l / 2),
        (palm_w * 1.1, t * 0.9, cuff_l),
        shade(color, 0.85),
        mat,
    )
    thumb_from = (palm_w / 2 - 0.01 * s, t / 2, -0.01 * s)
    thumb_to = (palm_w / 2 + 0.035 * s, t / 2, palm_l * 0.35)
    if style.shape == "oven":
        b.sphere(
            (0.0, t / 2, palm_l / 2),
            1.0,
            color,
            mat,
            segments=8,
            scale=(palm_w / 2, t / 2, 0.07 * s),
        )
        thumb = (palm_w / 2 + 0.012 * s, t / 2, 0.005 * s)
        b.sphere(thumb, 1.0, color, mat, segments=8, scale=(0.022 * s, t * 0.45, 0.05 * s))
        ring(
            b,
            (0.0, t / 2, -palm_l / 2 - cuff_l),
            0.015 * s,
            0.004 * s,
            0.006 * s,
            shade(color, 0.6),
            mat,
            axis="y",
            segments=6,
        )
        return ObjectModel(b.build())
    spread = float(rng.uniform(0.0, 0.15))
    for k in range(4):
        x = palm_w * (-0.375 + 0.25 * k)
        length = (0.06, 0.075, 0.07, 0.055)[k] * s
        angle = spread * (k - 1.5) / 1.5
        end = (x + length * math.sin(angle), t * 0.45, palm_l / 2 + length * math.cos(angle))
        beam(
            b,
            (x, t * 0.45, palm_l / 2 - 0.005 * s),
            end,
            0.02 * s,
            t * 0.85,
            color,
            mat,
            side=(1.0, 0.0, 0.0),
        )
    beam(b, thumb_from, thumb_to, 0.021 * s, t * 0.85, color, mat, side=(0.0, 1.0, 0.0))
    return ObjectModel(b.build())


def build_purse(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A handbag with two handles, a flat clutch with a flap, or a shoulder bag with a strap."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "clutch":
        w, h, d = 0.25 * s, 0.13 * s, 0.05 * s
        b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
        zf = d / 2 + 0.002
        flap = [(-w / 2, h, zf), (w / 2, h, zf), (w * 0.08, h * 0.4, zf), (-w * 0.08, h * 0.4, zf)]
        facing_polygon(
            b, [np.array(c) for c in flap], np.array((0.0, 0.0, 1.0)), shade(color, 0.7), mat
        )
        b.box((0.0, h * 0.42, d / 2 + 0.006), (0.025 * s, 0.012 * s, 0.006 * s), GOLD, METAL)
        return ObjectModel(b.build())
    handbag = style.shape == "handbag"
    w = (0.28 if handbag else 0.24) * s * float(rng.uniform(0.92, 1.05))
    h, d = (0.2 if handbag else 0.17) * s, 0.11 * s
    b.box((0.0, h * 0.4, 0.0), (w, h * 0.8, d), color, mat)
    b.box((0.0, h * 0.9, 0.0), (w * 0.9, h * 0.2, d * 0.85), color, mat)
    b.box((0.0, h * 0.55, d / 2 + 0.002), (0.02 * s, 0.02 * s, 0.004), GOLD, METAL)
    if handbag:
        for x in (-w * 0.22, w * 0.22):
            ring(
                b,
                (x, h, 0.0),
                0.06 * s,
                0.01 * s,
                0.01 * s,
                shade(color, 0.8),
                mat,
                segments=8,
                arc=(0.0, math.pi),
            )
    else:
        ring(
            b,
            (0.0, h * 0.85, 0.0),
            w * 0.5,
            0.012 * s,
            0.008 * s,
            shade(color, 0.8),
            mat,
            axis="x",
            segments=10,
            arc=(0.0, math.pi),
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="shoe",
        shapes={
            "sneakers": "pair of sneakers",
            "boots": "pair of boots",
            "heels": "pair of heels",
        },
        colors=WEAR_COLORS,
        materials=("leather", "fabric"),
        placement=Placement.AGAINST_WALL,
        rooms={"corridor": 0.5, "bedroom": 0.15},
        build=build_shoe,
    ),
    Category(
        name="hat",
        shapes={"sun": "sun hat", "fedora": "fedora", "beanie": "beanie"},
        colors=("beige", "black", "brown", "gray", "navy", "red", "cream", "white"),
        materials=("fabric", "plain"),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.12, "corridor": 0.15, "living room": 0.03},
        build=build_hat,
    ),
    Category(
        name="cap",
        shapes={"baseball": "baseball cap", "flat": "flat cap"},
        colors=("red", "blue", "navy", "black", "white", "gray", "green", "beige"),
        materials=("fabric",),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.12, "corridor": 0.1},
        build=build_cap,
    ),
    Category(
        name="glove",
        shapes={"winter": "winter glove", "oven": "oven glove", "rubber": "rubber glove"},
        colors=("black", "gray", "red", "yellow", "blue", "brown", "pink", "white"),
        materials=("fabric", "leather", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.15, "corridor": 0.1, "bedroom": 0.04, "storage room": 0.1},
        build=build_glove,
    ),
    Category(
        name="purse",
        shapes={"handbag": "handbag", "clutch": "clutch bag", "shoulder": "shoulder bag"},
        colors=("black", "brown", "red", "beige", "white", "navy", "pink", "dark green"),
        materials=("leather", "fabric"),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 0.15, "corridor": 0.15, "living room": 0.08},
        build=build_purse,
    ),
]
