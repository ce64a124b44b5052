"""Things to sit on: chairs, armchairs, sofas, stools, benches."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

WOOD_COLORS = ("brown", "dark brown", "beige", "white", "black")


def build_chair(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Four legs, a seat and a back; the office variant has a pedestal and a padded back."""
    s = style.scale
    color = color_rgb(style.color)
    mat = material_index(style.material)
    leg_color = color_rgb("black") if style.shape == "office" else color
    b = MeshBuilder()
    width, depth, seat_h = 0.45 * s, 0.45 * s, 0.46 * s
    back_h = 0.45 * s + float(rng.uniform(0.0, 0.1))
    seat_t = 0.05
    if style.shape == "office":
        b.cylinder((0.0, 0.0, 0.0), 0.03, seat_h - seat_t, leg_color, material_index("metal"))
        for k in range(5):
            angle = 2.0 * np.pi * k / 5
            b.box(
                (0.14 * np.cos(angle), 0.025, 0.14 * np.sin(angle)),
                (0.3, 0.04, 0.04),
                leg_color,
                material_index("plastic"),
                yaw=-angle,
            )
    else:
        leg = 0.04 * s
        for x in (-1, 1):
            for z in (-1, 1):
                b.box(
                    (x * (width / 2 - leg / 2), (seat_h - seat_t) / 2, z * (depth / 2 - leg / 2)),
                    (leg, seat_h - seat_t, leg),
                    leg_color,
                    mat,
                )
    b.box((0.0, seat_h - seat_t / 2, 0.0), (width, seat_t, depth), color, mat)
    back_t = 0.06 if style.shape == "office" else 0.035
    b.box(
        (0.0, seat_h + back_h / 2, -depth / 2 + back_t / 2),
        (width, back_h, back_t),
        color,
        mat,
    )
    return ObjectModel(b.build(), [Surface(seat_h, (0.0, 0.0), (width, depth))])


CATEGORIES = [
    Category(
        name="chair",
        shapes={"straight-backed": "dining chair", "office": "office chair"},
        colors=(*WOOD_COLORS, "red", "blue", "gray"),
        materials=("wood", "plastic", "metal", "leather"),
        placement=Placement.AT_TABLE,
        rooms={"dining room": 4.0, "kitchen": 1.0, "study": 1.0, "bedroom": 0.5,
               "living room": 1.0},
        build=build_chair,
    ),
]
