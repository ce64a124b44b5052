"""Exercise equipment and bicycles: long frames made of tubes, wheels and belts."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

GYM_COLORS = ("black", "gray", "dark gray", "silver", "white", "red")
BLACK = color_rgb("black")
DARK = color_rgb("dark gray")
PLASTIC = material_index("plastic")
METAL = material_index("metal")
SCREEN = (0.05, 0.1, 0.15)


def build_treadmill(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A long low deck with a dark belt, a motor hood, two uprights and a console (+z end)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    length, w = float(rng.uniform(1.6, 1.85)) * s, 0.75 * s
    deck_h, hood_d = 0.18 * s, 0.3 * s
    b = MeshBuilder()
    deck_z = -hood_d / 2
    b.box((0.0, deck_h / 2, deck_z), (w, deck_h, length - hood_d), color, mat)
    b.box(
        (0.0, deck_h + 0.003, deck_z),
        (w * 0.72, 0.006, length - hood_d - 0.06),
        BLACK,
        material_index("fabric"),
        faces="+y+z-z",
    )
    front = length / 2
    b.box((0.0, 0.14 * s, front - hood_d / 2), (w, 0.28 * s, hood_d), shade(color, 0.8), mat)
    top_y, top_z = 1.3 * s, front - 0.12 * s
    for x in (-1, 1):
        post = x * (w / 2 - 0.04 * s)
        beam(
            b,
            (post, 0.2 * s, front - 0.2 * s),
            (post, top_y, top_z),
            0.05 * s,
            0.06 * s,
            color,
            mat,
        )
        beam(
            b,
            (post, 1.0 * s, front - 0.18 * s),
            (post, 1.0 * s, front - 0.55 * s),
            0.035 * s,
            0.035 * s,
            DARK,
            PLASTIC,
        )
    beam(
        b,
        (0.0, top_y - 0.08 * s, top_z + 0.05 * s),
        (0.0, top_y + 0.1 * s, top_z - 0.02 * s),
        w * 0.8,
        0.06 * s,
        DARK,
        PLASTIC,
    )
    beam(
        b,
        (0.0, top_y - 0.04 * s, top_z + 0.02 * s),
        (0.0, top_y + 0.06 * s, top_z - 0.017 * s),
        w * 0.35,
        0.06 * s + 0.004,
        SCREEN,
        material_index("glass"),
    )
    return ObjectModel(b.build())


def build_exercise_bike(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Floor stabilisers, a frame with saddle and handlebars, and a flywheel at the front (+z)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    back, front = -0.5 * s, 0.45 * s
    for z in (back, front):
        b.cylinder((-0.25 * s, 0.03 * s, z), 0.03 * s, 0.5 * s, DARK, PLASTIC, segments=6, axis="x")
    crank = (0.0, 0.35 * s, 0.0)
    seat = (0.0, float(rng.uniform(0.85, 0.95)) * s, -0.3 * s)
    bars = (0.0, 1.1 * s, 0.3 * s)
    beam(b, (0.0, 0.05 * s, back), crank, 0.06 * s, 0.06 * s, color, mat)
    beam(b, crank, (0.0, 0.05 * s, front), 0.06 * s, 0.06 * s, color, mat)
    beam(b, crank, (0.0, seat[1] - 0.03 * s, seat[2]), 0.05 * s, 0.05 * s, color, mat)
    beam(b, (0.0, 0.3 * s, 0.28 * s), bars, 0.05 * s, 0.05 * s, color, mat)
    b.box((0.0, seat[1], seat[2]), (0.18 * s, 0.06 * s, 0.26 * s), BLACK, material_index("leather"))
    b.cylinder(
        (-0.22 * s, bars[1], bars[2]), 0.018 * s, 0.44 * s, BLACK, PLASTIC, segments=6, axis="x"
    )
    b.box(
        (0.0, bars[1] + 0.05 * s, bars[2] - 0.03 * s), (0.14 * s, 0.1 * s, 0.03 * s), DARK, PLASTIC
    )
    b.cylinder(
        (-0.03 * s, 0.38 * s, 0.33 * s),
        0.2 * s,
        0.06 * s,
        shade(color, 0.7),
        mat,
        segments=12,
        axis="x",
    )
    for x in (-1, 1):
        pedal = (x * 0.1 * s, 0.22 * s, 0.06 * s * x)
        beam(b, (x * 0.06 * s, crank[1], 0.0), pedal, 0.025 * s, 0.025 * s, DARK, METAL)
        b.box(pedal, (0.08 * s, 0.02 * s, 0.1 * s), BLACK, PLASTIC)
    return ObjectModel(b.build())


def build_exercise_ball(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A large inflatable ball."""
    r = float(rng.uniform(0.27, 0.33)) * style.scale
    b = MeshBuilder()
    b.sphere((0.0, r, 0.0), r, color_rgb(style.color), material_index(style.material), segments=12)
    return ObjectModel(b.build())


def _wheel(b: MeshBuilder, x: float, r: float, tire: float, spokes: Rgb) -> None:
    """A tyre in the x-y plane with four spokes."""
    ring(b, (x, r, 0.0), r, tire, tire, BLACK, PLASTIC, segments=10, arc=(-np.pi / 2, 1.5 * np.pi))
    for dx, dy in ((1.0, 0.0), (0.0, 1.0)):
        reach = r - tire
        beam(
            b,
            (x - dx * reach, r - dy * reach, 0.0),
            (x + dx * reach, r + dy * reach, 0.0),
            0.006,
            0.006,
            spokes,
            METAL,
            side=(0.0, 0.0, 1.0),
        )


def build_bicycle(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Two wheels, a diamond frame, saddle and handlebars; parked along x (front at +x)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    mountain = style.shape == "mountain"
    r, tire = 0.34 * s, (0.055 if mountain else 0.035) * s
    rear, front = -0.52 * s, 0.52 * s
    silver = color_rgb("silver")
    b = MeshBuilder()
    _wheel(b, rear, r, tire, silver)
    _wheel(b, front, r, tire, silver)
    bb = (-0.05 * s, 0.3 * s, 0.0)
    seat_top = (-0.18 * s, (0.8 if mountain else 0.86) * s, 0.0)
    head_top, head_low = (0.36 * s, 0.88 * s, 0.0), (0.4 * s, 0.72 * s, 0.0)
    tube = 0.035 * s
    for p0, p1 in (
        (bb, seat_top),
        (bb, head_low),
        (seat_top, head_top),
        (head_top, head_low),
        (bb, (rear, r, 0.0)),
        ((-0.17 * s, 0.78 * s, 0.0), (rear, r, 0.0)),
        (head_low, (front, r, 0.0)),
    ):
        beam(b, p0, p1, tube, tube, color, mat, side=(0.0, 0.0, 1.0))
    saddle_y = seat_top[1] + float(rng.uniform(0.06, 0.12)) * s
    beam(b, seat_top, (seat_top[0] - 0.02 * s, saddle_y, 0.0), 0.025 * s, 0.025 * s, silver, METAL)
    b.box(
        (seat_top[0] - 0.03 * s, saddle_y, 0.0),
        (0.24 * s, 0.05 * s, 0.12 * s),
        BLACK,
        material_index("leather"),
    )
    bar = (head_top[0] - 0.03 * s, head_top[1] + 0.1 * s, 0.0)
    beam(b, head_top, bar, 0.03 * s, 0.03 * s, silver, METAL)
    b.cylinder((bar[0], bar[1], -0.28 * s), 0.014 * s, 0.56 * s, BLACK, METAL, segments=6, axis="z")
    for z in (-1, 1):
        pedal = (bb[0] + 0.06 * s * z, bb[1] - 0.15 * s * z, z * 0.09 * s)
        beam(b, (bb[0], bb[1], z * 0.04 * s), pedal, 0.02 * s, 0.02 * s, silver, METAL)
        b.box(pedal, (0.1 * s, 0.02 * s, 0.08 * s), BLACK, PLASTIC)
    if style.shape == "city":
        b.box(
            (front + 0.06 * s, 0.82 * s, 0.0),
            (0.28 * s, 0.2 * s, 0.3 * s),
            color_rgb("brown"),
            material_index("wood"),
            faces="+x-x+z-z-y",
        )
        b.box((rear + 0.05 * s, 0.74 * s, 0.0), (0.36 * s, 0.02, 0.14 * s), silver, METAL)
    return ObjectModel(b.build())


def build_exercise_equipment(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An exercise bike or an exercise ball, by shape."""
    if style.shape == "ball":
        return build_exercise_ball(style, rng)
    return build_exercise_bike(style, rng)


CATEGORIES: list[Category] = [
    Category(
        name="treadmill",
        shapes={"folding": "treadmill"},
        colors=GYM_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.FLOOR,
        rooms={"gym": 0.8, "living room": 0.03, "bedroom": 0.03, "storage room": 0.05},
        build=build_treadmill,
    ),
    Category(
        name="excercise equipment",  # the reference's spelling
        shapes={"bike": "exercise bike", "ball": "exercise ball"},
        colors=(*GYM_COLORS, "blue", "purple", "pink", "green"),
        materials=("plastic",),  # a "metal exercise ball" is no thing
        placement=Placement.FLOOR,
        rooms={"gym": 1.3, "living room": 0.1, "bedroom": 0.1, "study": 0.04},
        build=build_exercise_equipment,
    ),
    Category(
        name="bicycle",
        shapes={"city": "city bike", "mountain": "mountain bike", "road": "road bike"},
        colors=("red", "blue", "black", "white", "green", "silver", "yellow", "orange"),
        materials=("metal",),
        placement=Placement.AGAINST_WALL,
        rooms={"corridor": 0.15, "storage room": 0.35, "gym": 0.1},
        build=build_bicycle,
    ),
]
