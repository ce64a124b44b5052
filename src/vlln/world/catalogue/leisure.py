"""Drums, umbrellas and people: things that stand on the floor but are no furniture.

A person is a standing figure, shaped and proportioned so that it reads as a person at a
glance (head, torso, arms, legs, shoes); it never moves.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

METAL = material_index("metal")
PLASTIC = material_index("plastic")
FABRIC = material_index("fabric")
BLACK = color_rgb("black")
SILVER = color_rgb("silver")
GOLD = color_rgb("gold")
SKIN_TONES = ((0.86, 0.67, 0.53), (0.62, 0.43, 0.3), (0.36, 0.23, 0.15), (0.93, 0.78, 0.66))
HAIR = ((0.1, 0.07, 0.05), (0.35, 0.22, 0.1), (0.75, 0.6, 0.35), (0.5, 0.5, 0.5))


def _drum(
    b: MeshBuilder,
    x: float,
    y: float,
    z: float,
    r: float,
    depth: float,
    shell: Rgb,
    mat: int,
    axis: str = "y",
) -> None:
    """A drum shell with a white head and a metal hoop, its base centre at ``(x, y, z)``."""
    b.cylinder((x, y, z), r, depth, shell, mat, segments=10, caps=False, axis=axis)
    top = {"y": (x, y + depth, z), "z": (x, y, z + depth), "x": (x + depth, y, z)}[axis]
    b.cylinder(top, r * 0.97, 0.004, (0.95, 0.94, 0.9), PLASTIC, segments=10, axis=axis)
    rim = {
        "y": (x, y + depth - 0.02, z),
        "z": (x, y, z + depth - 0.02),
        "x": (x + depth - 0.02, y, z),
    }
    b.cylinder(rim[axis], r * 1.03, 0.025, SILVER, METAL, segments=10, caps=False, axis=axis)


def _cymbal(b: MeshBuilder, x: float, z: float, h: float, r: float) -> None:
    b.cylinder((x, 0.0, z), 0.012, h, SILVER, METAL, segments=6)
    b.cylinder((x, h, z), r, 0.012, GOLD, METAL, segments=10, radius_top=0.02)


def build_drum(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A drum kit (bass drum on its side, snare, toms and cymbals on stands) or a single
    floor drum on short legs."""
    s = style.scale
    shell, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "floor":
        r, depth = 0.2 * s, 0.45 * s
        for k in range(3):
            a = 2.0 * math.pi * k / 3
            b.box(
                (r * math.cos(a), 0.06 * s, r * math.sin(a)), (0.02, 0.12 * s, 0.02), SILVER, METAL
            )
        _drum(b, 0.0, 0.1 * s, 0.0, r, depth, shell, mat)
        return ObjectModel(standing_on_floor(b.build()))
    bass_r = 0.28 * s
    _drum(b, 0.0, bass_r, -0.18 * s, bass_r, 0.36 * s, shell, mat, axis="z")
    for x in (-0.14 * s, 0.14 * s):
        _drum(b, x, 0.68 * s, -0.05 * s, 0.12 * s, 0.16 * s, shell, mat)
    b.cylinder((0.42 * s, 0.0, 0.15 * s), 0.012, 0.5 * s, SILVER, METAL, segments=6)
    _drum(b, 0.42 * s, 0.5 * s, 0.15 * s, 0.17 * s, 0.12 * s, shell, mat)
    for leg in range(3):
        a = 2.0 * math.pi * leg / 3
        foot = (-0.5 * s + 0.22 * s * math.cos(a), 0.0, 0.1 * s + 0.22 * s * math.sin(a))
        b.box(foot, (0.03, 0.02, 0.03), BLACK, METAL)
    _drum(b, -0.5 * s, 0.0, 0.1 * s, 0.2 * s, 0.45 * s, shell, mat)
    _cymbal(b, -0.45 * s, -0.35 * s, 1.15 * s, 0.22 * s)
    _cymbal(b, 0.5 * s, -0.3 * s, 1.05 * s, 0.18 * s)
    return ObjectModel(standing_on_floor(b.build()))


def _triangle(
    b: MeshBuilder,
    corners: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    outward: NDArray[np.float64],
    color: Rgb,
    mat: int,
) -> None:
    """One flat triangle facing ``outward``."""
    p = np.array(corners)
    normal = np.cross(p[1] - p[0], p[2] - p[0])
    if float(np.dot(normal, outward)) < 0.0:
        p, normal = p[::-1], -normal
    normal /= float(np.linalg.norm(normal))
    uv = np.array([(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)])
    b.add_triangles(p, np.tile(normal, (3, 1)), uv, color, mat)


def build_umbrella(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A long closed umbrella on its tip with a crook handle, or an open one drying, its
    canopy of eight panels resting on the floor."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    handle = color_rgb("dark brown")
    if style.shape == "closed":
        h = 0.9 * s
        b.cylinder((0.0, 0.0, 0.0), 0.006, 0.08 * s, SILVER, METAL, segments=6)
        b.cylinder(
            (0.0, 0.08 * s, 0.0), 0.015, 0.55 * s, color, mat, segments=8, radius_top=0.04 * s
        )
        b.cylinder(
            (0.0, 0.63 * s, 0.0), 0.04 * s, 0.04 * s, color, mat, segments=8, radius_top=0.012
        )
        b.cylinder((0.0, 0.67 * s, 0.0), 0.008, h - 0.75 * s, SILVER, METAL, segments=6)
        ring(
            b,
            (0.05 * s, h - 0.08 * s, 0.0),
            0.065 * s,
            0.022,
            0.022,
            handle,
            material_index("wood"),
            "z",
            7,
            (0.0, math.pi),
        )
        return ObjectModel(b.build())
    r, rise, n = 0.5 * s, 0.35 * s, 8
    apex = np.array([0.0, rise + 0.02, 0.0])
    for k in range(n):
        a0, a1 = 2.0 * math.pi * k / n, 2.0 * math.pi * (k + 1) / n
        p0 = np.array([r * math.cos(a0), 0.02, r * math.sin(a0)])
        p1 = np.array([r * math.cos(a1), 0.02, r * math.sin(a1)])
        mid = (p0 + p1) / 2
        out = np.array([mid[0], 0.6 * r, mid[2]])
        tone = color if k % 2 == 0 else shade(color, 0.85)
        _triangle(b, (p0, p1, apex), out, tone, mat)
        _triangle(b, (p0, p1, apex), -out, shade(tone, 0.7), mat)  # the inside, seen below
        b.cylinder((p0[0], 0.0, p0[2]), 0.01, 0.025, SILVER, METAL, segments=5)
    b.cylinder((0.0, rise + 0.02, 0.0), 0.008, 0.05, SILVER, METAL, segments=6)
    beam(
        b, (0.0, rise * 0.9, 0.0), (0.1 * s, rise + 0.45 * s, 0.35 * s), 0.016, 0.016, SILVER, METAL
    )
    b.cylinder(
        (0.1 * s, rise + 0.45 * s, 0.35 * s), 0.02, 0.12 * s, handle, material_index("wood"), 8
    )
    return ObjectModel(b.build())


def build_person(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A standing adult or child: shoes, trousers or a skirt, a shirt of the style's colour
    with arms at its sides, a neck, a head with hair."""
    s = style.scale * (0.72 if style.shape == "child" else 1.0)
    shirt, mat = color_rgb(style.color), material_index(style.material)
    skin = SKIN_TONES[int(rng.integers(len(SKIN_TONES)))]
    hair = HAIR[int(rng.integers(len(HAIR)))]
    trousers = color_rgb(str(rng.choice(["navy", "black", "dark gray", "beige", "blue"])))
    height = float(rng.uniform(1.65, 1.85)) * s
    u = height / 1.75
    b = MeshBuilder()
    for x in (-0.1 * u, 0.1 * u):
        b.box(
            (x, 0.04 * u, 0.03 * u), (0.1 * u, 0.08 * u, 0.26 * u), BLACK, material_index("leather")
        )
        b.cylinder(
            (x, 0.08 * u, 0.0), 0.065 * u, 0.78 * u, trousers, FABRIC, 10, radius_top=0.085 * u
        )
    b.box((0.0, 0.88 * u, 0.0), (0.36 * u, 0.14 * u, 0.22 * u), trousers, FABRIC)
    b.cylinder((0.0, 0.94 * u, 0.0), 0.2 * u, 0.5 * u, shirt, mat, 12, radius_top=0.22 * u)
    b.sphere((0.0, 1.44 * u, 0.0), 0.22 * u, shirt, mat, segments=10, scale=(1.0, 0.3, 0.6))
    for sx in (-1.0, 1.0):
        shoulder = (sx * 0.23 * u, 1.4 * u, 0.0)
        elbow = (sx * 0.27 * u, 1.12 * u, 0.02 * u)
        wrist = (sx * 0.28 * u, 0.86 * u, 0.06 * u)
        beam(b, shoulder, elbow, 0.1 * u, 0.1 * u, shirt, mat)
        beam(b, elbow, wrist, 0.08 * u, 0.08 * u, skin, PLASTIC)
        b.sphere((wrist[0], wrist[1] - 0.04 * u, wrist[2]), 0.045 * u, skin, PLASTIC, segments=6)
    b.cylinder((0.0, 1.44 * u, 0.0), 0.05 * u, 0.1 * u, skin, PLASTIC, segments=8)
    head_y = 1.63 * u
    b.sphere((0.0, head_y, 0.0), 0.11 * u, skin, PLASTIC, segments=10, scale=(0.85, 1.05, 0.95))
    b.sphere(
        (0.0, head_y + 0.035 * u, -0.015 * u),
        0.112 * u,
        hair,
        FABRIC,
        segments=10,
        scale=(0.88, 0.9, 0.95),
    )
    for x in (-0.035 * u, 0.035 * u):
        b.sphere((x, head_y + 0.01 * u, 0.095 * u), 0.012 * u, BLACK, PLASTIC, segments=4)
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="drum",
        shapes={"kit": "drum kit", "floor": "floor drum"},
        colors=("red", "black", "blue", "white", "silver", "brown"),
        materials=("wood", "plastic"),
        placement=Placement.CORNER,
        rooms={"living room": 0.03, "bedroom": 0.03, "study": 0.03, "storage room": 0.05},
        build=build_drum,
    ),
    Category(
        name="umbrella",
        shapes={"closed": "closed umbrella", "open": "open umbrella"},
        colors=("black", "navy", "red", "blue", "yellow", "green", "purple", "pink"),
        materials=("fabric",),
        placement=Placement.CORNER,
        rooms={"corridor": 0.3, "storage room": 0.05, "bathroom": 0.03},
        build=build_umbrella,
    ),
    Category(
        name="person",
        shapes={"adult": "standing person", "child": "standing child"},
        colors=("blue", "red", "white", "green", "gray", "black", "yellow", "pink"),
        materials=("fabric",),
        placement=Placement.FLOOR,
        rooms={"living room": 0.1, "kitchen": 0.08, "bedroom": 0.04, "study": 0.05, "gym": 0.1},
        build=build_person,
    ),
]
