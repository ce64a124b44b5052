"""Small things fixed to walls: switches, sockets, plugs, hooks, hangers, signs, blackboards.

Every model here is wall-mounted: its back is on z = 0 and its bottom on y = 0, and
``wall_height`` lifts it to its usual height (switches by the door handle, sockets near the
floor). The small ones are drawn a little larger than life so an agent can see them at all.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade, standing_on_floor
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

PLASTIC = material_index("plastic")
METAL = material_index("metal")
WOOD = material_index("wood")
BLACK = color_rgb("black")
DARK = color_rgb("dark gray")
WHITE = color_rgb("white")
ROOMS_WITH_POWER = ("living room", "bedroom", "kitchen", "dining room", "study", "corridor")


def _plate(b: MeshBuilder, w: float, h: float, y: float, style: Style) -> None:
    """A wall plate of the style's colour, ``w`` x ``h``, its bottom at ``y``."""
    color, mat = color_rgb(style.color), material_index(style.material)
    b.box((0.0, y + h / 2, 0.006), (w, h, 0.012), color, mat, faces="+x-x+y-y+z")


def build_switch(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A square plate with one or two rocker buttons."""
    s = style.scale
    size = 0.09 * s
    b = MeshBuilder()
    _plate(b, size * (1.7 if style.shape == "double" else 1.0), size, 0.0, style)
    rocker = shade(color_rgb(style.color), 0.85)
    n = 2 if style.shape == "double" else 1
    for k in range(n):
        x = (k - (n - 1) / 2) * size * 0.75
        b.box((x, size / 2, 0.016), (size * 0.5, size * 0.62, 0.01), rocker, PLASTIC)
        b.box((x, size * 0.62, 0.0215), (size * 0.4, 0.004, 0.002), DARK, PLASTIC, faces="+z")
    return ObjectModel(b.build())


def _outlet(b: MeshBuilder, x: float, y: float, r: float) -> None:
    """A round recessed outlet with two pin holes."""
    b.cylinder((x, y, 0.012), r, 0.004, shade(WHITE, 0.85), PLASTIC, segments=10, axis="z")
    for dx in (-0.35 * r, 0.35 * r):
        b.box((x + dx, y, 0.0165), (0.12 * r, 0.12 * r, 0.001), BLACK, PLASTIC, faces="+z")


def build_socket(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wall plate with one or two round outlets."""
    s = style.scale
    size = 0.09 * s
    n = 2 if style.shape == "double" else 1
    b = MeshBuilder()
    _plate(b, size * (1.8 if n == 2 else 1.0), size, 0.0, style)
    for k in range(n):
        _outlet(b, (k - (n - 1) / 2) * size * 0.85, size / 2, size * 0.33)
    return ObjectModel(b.build())


def build_plug(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A plug in a wall socket, its cable running down to the floor (a charger brick has a
    thin white cable)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    size = 0.09 * s
    y0 = 0.3 * s  # the socket's bottom; the model starts on the floor
    b = MeshBuilder()
    b.box((0.0, y0 + size / 2, 0.006), (size, size, 0.012), WHITE, PLASTIC)
    charger = style.shape == "charger"
    body = (0.05 * s, 0.06 * s, 0.05 * s) if charger else (0.045 * s, 0.055 * s, 0.035 * s)
    b.box((0.0, y0 + size / 2, 0.012 + body[2] / 2), body, color, mat)
    cable = WHITE if charger else DARK
    thick = 0.008 if charger else 0.012
    bottom = y0 + size / 2 - body[1] / 2
    z_out = 0.012 + body[2] / 2
    # the cable sags from the plug in a curve to the floor, then lies along it in a loop
    points = [(0.0, bottom, z_out)]
    for k in range(1, 5):
        f = k / 4
        points.append(
            (0.03 * s * f, bottom * (1.0 - f) ** 1.5, z_out + 0.08 * s * math.sin(f * 1.6))
        )
    points += [(0.12 * s, 0.0, z_out + 0.16 * s), (0.22 * s, 0.0, z_out + 0.08 * s)]
    for p0, p1 in itertools.pairwise(points):
        beam(b, p0, p1, thick, thick, cable, PLASTIC)
    return ObjectModel(standing_on_floor(b.build()))


def build_hook(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A board with a row of curved hooks (rail), or one large hook on a round rose."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    metal = color_rgb("silver") if style.material != "metal" else shade(color, 0.8)
    b = MeshBuilder()
    if style.shape == "rail":
        n = int(rng.integers(3, 6))
        w = 0.13 * n * s
        b.box((0.0, 0.05 * s, 0.01), (w, 0.1 * s, 0.02), color, mat)
        hooks = [((k - (n - 1) / 2) * 0.13 * s, 0.06 * s) for k in range(n)]
        depth, r = 0.02, 0.035 * s
    else:
        b.cylinder((0.0, 0.05 * s, 0.0), 0.04 * s, 0.015, color, mat, segments=10, axis="z")
        hooks = [(0.0, 0.06 * s)]
        depth, r = 0.015, 0.05 * s
    for x, y in hooks:
        beam(b, (x, y, depth), (x, y - 0.01 * s, depth + 0.06 * s), 0.012, 0.012, metal, METAL)
        ring(
            b,
            (x, y - 0.01 * s + r, depth + 0.06 * s),
            r,
            0.012,
            0.012,
            metal,
            METAL,
            axis="x",
            segments=5,
            arc=(math.pi * 0.5, math.pi * 1.5),
        )
    return ObjectModel(standing_on_floor(b.build()))


def build_hanger(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A coat hanger on a wall hook: a hook over a shoulder bar or triangle, maybe a shirt."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w = 0.42 * s
    top = 0.42 * s  # the hook's top
    shoulder_y = top - 0.14 * s
    z = 0.05 * s
    metal = color_rgb("silver")
    b = MeshBuilder()
    b.cylinder((0.0, top - 0.01 * s, 0.0), 0.02 * s, 0.015, DARK, METAL, segments=6, axis="z")
    ring(b, (0.0, top - 0.035 * s, z), 0.03 * s, 0.006, 0.006, metal, METAL, "z", 6, (0.0, math.pi))
    beam(
        b,
        (-0.03 * s, top - 0.035 * s, z),
        (0.0, shoulder_y + 0.02 * s, z),
        0.006,
        0.006,
        metal,
        METAL,
    )
    for sx in (-1.0, 1.0):
        beam(
            b,
            (0.0, shoulder_y + 0.02 * s, z),
            (sx * w / 2, shoulder_y - 0.08 * s, z),
            0.02 * s,
            0.012 * s,
            color,
            mat,
        )
    if style.shape == "with shirt":
        shirt = color_rgb(str(rng.choice(["light blue", "white", "navy", "red", "gray"])))
        fabric = material_index("fabric")
        b.box((0.0, shoulder_y - 0.3 * s, z + 0.02), (w * 0.85, 0.44 * s, 0.03 * s), shirt, fabric)
        for sx in (-1.0, 1.0):
            beam(
                b,
                (sx * w * 0.4, shoulder_y - 0.1 * s, z + 0.02),
                (sx * w * 0.5, shoulder_y - 0.35 * s, z + 0.02),
                0.1 * s,
                0.03 * s,
                shirt,
                fabric,
            )
        b.box(
            (0.0, shoulder_y - 0.1 * s, z + 0.037 * s),
            (0.08 * s, 0.06 * s, 0.004),
            shade(shirt, 0.8),
            fabric,
        )
    else:
        beam(
            b,
            (-w / 2, shoulder_y - 0.08 * s, z),
            (w / 2, shoulder_y - 0.08 * s, z),
            0.012 * s,
            0.012 * s,
            color,
            mat,
        )
    return ObjectModel(standing_on_floor(b.build()))


def build_sign(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A plate with a pictogram: a green exit sign with a running figure and an arrow, or a
    notice plate with a title bar and lines of text."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "exit":
        w, h = 0.36 * s, 0.16 * s
        b.box((0.0, h / 2, 0.02), (w, h, 0.04), color, mat)
        figure = WHITE
        cx, cy, zf = -w * 0.25, h / 2, 0.0405
        b.cylinder(
            (cx + 0.01 * s, cy + 0.045 * s, zf), 0.013 * s, 0.001, figure, PLASTIC, 8, axis="z"
        )
        for p0, p1 in (
            ((cx, cy + 0.03 * s), (cx - 0.01 * s, cy - 0.01 * s)),
            ((cx - 0.01 * s, cy - 0.01 * s), (cx + 0.02 * s, cy - 0.05 * s)),
            ((cx - 0.01 * s, cy - 0.01 * s), (cx - 0.04 * s, cy - 0.05 * s)),
            ((cx - 0.005 * s, cy + 0.02 * s), (cx + 0.03 * s, cy + 0.005 * s)),
            ((cx - 0.005 * s, cy + 0.02 * s), (cx - 0.035 * s, cy + 0.01 * s)),
        ):
            beam(b, (*p0, zf), (*p1, zf), 0.012 * s, 0.002, figure, PLASTIC, side=(0.0, 0.0, 1.0))
        ax = w * 0.15
        beam(
            b,
            (ax, cy, zf),
            (ax + 0.09 * s, cy, zf),
            0.015 * s,
            0.002,
            figure,
            PLASTIC,
            side=(0.0, 1.0, 0.0),
        )
        for dy in (-1.0, 1.0):
            beam(
                b,
                (ax + 0.09 * s, cy, zf),
                (ax + 0.06 * s, cy + dy * 0.03 * s, zf),
                0.012 * s,
                0.002,
                figure,
                PLASTIC,
                side=(0.0, 0.0, 1.0),
            )
        return ObjectModel(b.build())
    w, h = 0.3 * s, 0.4 * s
    b.box((0.0, h / 2, 0.008), (w, h, 0.016), WHITE, PLASTIC)
    b.box((0.0, h * 0.86, 0.0165), (w * 0.9, h * 0.16, 0.002), color, mat, faces="+z")
    lines = int(rng.integers(5, 8))
    for k in range(lines):
        length = w * float(rng.uniform(0.5, 0.85))
        y = h * (0.68 - 0.09 * k)
        b.box(
            (-w * 0.42 + length / 2, y, 0.0165),
            (length, 0.012 * s, 0.002),
            DARK,
            PLASTIC,
            faces="+z",
        )
    return ObjectModel(b.build())


def build_blackboard(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A dark board in a frame with a chalk tray, and chalk lines written on it."""
    s = style.scale
    board = color_rgb(style.color)
    frame_mat = material_index(style.material)
    frame = color_rgb("brown") if style.material == "wood" else color_rgb("silver")
    w = (1.2 if style.shape == "wide" else 0.8) * s
    h = (0.9 if style.shape == "wide" else 0.6) * s
    t = 0.04 * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.01), (w - t, h - t, 0.02), board, material_index("plain"))
    for y in (t / 2, h - t / 2):
        b.box((0.0, y, 0.015), (w, t, 0.03), frame, frame_mat)
    for x in (-w / 2 + t / 2, w / 2 - t / 2):
        b.box((x, h / 2, 0.015), (t, h - 2 * t, 0.03), frame, frame_mat)
    b.box((0.0, t, 0.05), (w * 0.9, 0.015, 0.05), frame, frame_mat)
    chalk = (0.95, 0.95, 0.92)
    b.box((w * 0.2, t + 0.015, 0.05), (0.08 * s, 0.015, 0.015), chalk, PLASTIC)
    for k in range(int(rng.integers(3, 6))):
        length = w * float(rng.uniform(0.3, 0.7))
        x0 = -w * 0.4
        y = h * (0.8 - 0.13 * k)
        b.box((x0 + length / 2, y, 0.0205), (length, 0.012 * s, 0.001), chalk, PLASTIC, faces="+z")
    return ObjectModel(b.build())


PLATE_COLORS = ("white", "cream", "black", "silver", "gray")

CATEGORIES: list[Category] = [
    Category(
        name="switch",
        shapes={"single": "light switch", "double": "double light switch"},
        colors=PLATE_COLORS,
        materials=("plastic", "metal"),
        placement=Placement.WALL_MOUNTED,
        rooms={**dict.fromkeys(ROOMS_WITH_POWER, 0.35), "bathroom": 0.3, "toilet": 0.3},
        build=build_switch,
        wall_height=1.1,
    ),
    Category(
        name="socket",
        shapes={"single": "wall socket", "double": "double wall socket"},
        colors=PLATE_COLORS,
        materials=("plastic", "metal"),
        placement=Placement.WALL_MOUNTED,
        rooms={**dict.fromkeys(ROOMS_WITH_POWER, 0.35), "gym": 0.2},
        build=build_socket,
        wall_height=0.3,
    ),
    Category(
        name="plug",
        shapes={"plug": "power plug", "charger": "phone charger"},
        colors=("black", "white", "gray"),
        materials=("plastic",),
        placement=Placement.WALL_MOUNTED,
        rooms={"living room": 0.15, "bedroom": 0.2, "study": 0.2, "kitchen": 0.1},
        build=build_plug,
        wall_height=0.0,
    ),
    Category(
        name="hook",
        shapes={"rail": "coat hook rail", "single": "wall hook"},
        colors=("brown", "white", "black", "silver", "dark brown"),
        materials=("wood", "metal"),
        placement=Placement.WALL_MOUNTED,
        rooms={"corridor": 0.5, "bathroom": 0.3, "bedroom": 0.15, "toilet": 0.1},
        build=build_hook,
        wall_height=1.6,
    ),
    Category(
        name="hanger",
        shapes={"empty": "coat hanger", "with shirt": "shirt on a hanger"},
        colors=("brown", "black", "white", "beige"),
        materials=("wood", "plastic"),
        placement=Placement.WALL_MOUNTED,
        rooms={"bedroom": 0.2, "corridor": 0.15, "storage room": 0.1},
        build=build_hanger,
        wall_height=1.35,
    ),
    Category(
        name="sign",
        shapes={"exit": "exit sign", "notice": "notice sign"},
        colors=("green", "red", "blue", "yellow"),
        materials=("plastic",),
        placement=Placement.WALL_MOUNTED,
        rooms={"corridor": 0.15, "gym": 0.2, "storage room": 0.1, "kitchen": 0.05},
        build=build_sign,
        wall_height=1.9,
    ),
    Category(
        name="blackboard",
        shapes={"wide": "blackboard", "small": "small chalkboard"},
        colors=("black", "dark green", "dark gray"),
        materials=("wood", "metal"),
        placement=Placement.WALL_MOUNTED,
        rooms={"study": 0.15, "kitchen": 0.1, "bedroom": 0.05},
        build=build_blackboard,
        wall_height=0.95,
    ),
]
