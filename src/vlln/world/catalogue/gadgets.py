"""Small electronics: telephones, cameras, tablets, remote controls, mice and radios.

Every model stands on a desk, a table or a shelf and fits a 0.4 x 0.3 m footprint at the
largest scale. Screens are dark with a few bright tiles so that they read as switched on.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, rotated_about_x, shade, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder

GADGET_COLORS = ("black", "white", "silver", "gray", "dark gray", "red", "blue")
PLAIN = material_index("plain")
PLASTIC = material_index("plastic")
GLASS = material_index("glass")
METAL = material_index("metal")
SCREEN = color_rgb("black")
APP_COLORS = ("blue", "green", "orange", "red", "yellow", "light blue", "purple")


def _buttons(
    b: MeshBuilder,
    center: tuple[float, float, float],
    grid: tuple[int, int],
    pitch: float,
    size: float,
    color: Rgb,
) -> None:
    """A grid of small raised buttons on a horizontal face whose top is at ``center[1]``."""
    cols, rows = grid
    x0, y, z0 = center
    for i in range(cols):
        for j in range(rows):
            x = x0 + (i - (cols - 1) / 2) * pitch
            z = z0 + (j - (rows - 1) / 2) * pitch
            b.box((x, y + 0.002, z), (size, 0.004, size), color, PLASTIC)


def _keys_color(color: Rgb) -> Rgb:
    """Buttons that stand out from the body: light on dark bodies, dark on light ones."""
    return shade(color, 0.45) if sum(color) > 1.5 else color_rgb("light gray")


def build_telephone(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A desk phone with a handset on its cradle and a keypad, or a cordless phone in its dock."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    keys = _keys_color(color)
    b = MeshBuilder()
    if style.shape == "cordless":
        b.box((0.0, 0.015 * s, 0.0), (0.08 * s, 0.03 * s, 0.09 * s), color, mat)
        top = (0.0, 0.17 * s, -0.015 * s)
        beam(
            b,
            (0.0, 0.02 * s, -0.005 * s),
            top,
            0.05 * s,
            0.022 * s,
            color,
            mat,
            side=(1.0, 0.0, 0.0),
        )
        b.box((0.0, 0.135 * s, -0.006 * s), (0.034 * s, 0.035 * s, 0.004 * s), SCREEN, GLASS)
        for k in range(4):
            y = 0.05 * s + k * 0.017 * s
            for x in (-0.012 * s, 0.0, 0.012 * s):
                b.box((x, y, 0.004 * s), (0.008 * s, 0.008 * s, 0.004 * s), keys, PLASTIC)
        return ObjectModel(b.build())
    w, d = 0.2 * s, float(rng.uniform(0.17, 0.2)) * s
    b.box((0.0, 0.025 * s, 0.0), (w, 0.05 * s, d), color, mat)
    beam(
        b,
        (0.0, 0.05 * s, d * 0.45),
        (0.0, 0.075 * s, -d * 0.05),
        w * 0.9,
        0.01 * s,
        shade(color, 0.9),
        mat,
    )
    _buttons(b, (w * 0.15, 0.062 * s, d * 0.22), (3, 4), 0.022 * s, 0.014 * s, keys)
    b.box((-w * 0.25, 0.066 * s, d * 0.2), (0.05 * s, 0.004 * s, 0.03 * s), SCREEN, GLASS)
    y = 0.085 * s
    b.box((0.0, y, -d * 0.3), (w * 0.95, 0.025 * s, 0.05 * s), color, mat)
    for x in (-1, 1):
        b.box((x * w * 0.4, y - 0.004 * s, -d * 0.3), (0.05 * s, 0.035 * s, 0.06 * s), color, mat)
    ring(
        b,
        (w * 0.5, 0.03 * s, -d * 0.3),
        0.02 * s,
        0.004 * s,
        0.02 * s,
        shade(color, 0.7),
        mat,
        axis="x",
        segments=8,
    )
    return ObjectModel(b.build())


def build_camera(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A compact digital camera with a small lens, or a professional one with a big lens."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    black = color_rgb("black")
    if style.shape == "digital":
        w, h, d = 0.1 * s, 0.06 * s, 0.03 * s
        b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
        b.cylinder(
            (0.015 * s, h / 2, d / 2),
            0.02 * s,
            0.012 * s,
            color_rgb("silver"),
            METAL,
            segments=10,
            axis="z",
        )
        b.cylinder(
            (0.015 * s, h / 2, d / 2 + 0.012 * s),
            0.013 * s,
            0.002 * s,
            black,
            GLASS,
            segments=10,
            axis="z",
        )
        b.box(
            (-0.03 * s, h * 0.8, d / 2 + 0.001),
            (0.015 * s, 0.008 * s, 0.002),
            color_rgb("white"),
            PLAIN,
        )
        b.box(
            (0.03 * s, h + 0.002 * s, 0.0),
            (0.012 * s, 0.004 * s, 0.01 * s),
            color_rgb("silver"),
            METAL,
        )
        return ObjectModel(b.build())
    w, h, d = 0.14 * s, 0.09 * s, 0.07 * s
    b.box((0.0, h * 0.4, 0.0), (w, h * 0.8, d), color, mat)
    b.box((-w * 0.4, h * 0.4, 0.01 * s), (w * 0.22, h * 0.8, d * 1.2), shade(color, 0.8), mat)
    b.box((0.0, h * 0.9, -0.005 * s), (0.05 * s, h * 0.22, d * 0.7), color, mat)
    lens = float(rng.uniform(0.06, 0.09)) * s
    b.cylinder((0.01 * s, h * 0.42, d / 2), 0.032 * s, lens, black, PLASTIC, segments=12, axis="z")
    b.cylinder(
        (0.01 * s, h * 0.42, d / 2 + lens * 0.6),
        0.0335 * s,
        lens * 0.2,
        color_rgb("dark gray"),
        PLASTIC,
        segments=12,
        axis="z",
        caps=False,
    )
    b.cylinder(
        (0.01 * s, h * 0.42, d / 2 + lens),
        0.025 * s,
        0.001,
        color_rgb("navy"),
        GLASS,
        segments=12,
        axis="z",
    )
    return ObjectModel(b.build())


def _screen(b: MeshBuilder, w: float, d: float, y: float, rng: np.random.Generator) -> None:
    """A dark screen on a horizontal face at height ``y``, with rows of bright app tiles."""
    b.box((0.0, y + 0.0005, 0.0), (w, 0.001, d), SCREEN, GLASS, faces="+y")
    tile = min(w, d) / 6
    for i in range(4):
        for j in range(5):
            color = color_rgb(APP_COLORS[int(rng.integers(len(APP_COLORS)))])
            x, z = (i - 1.5) * w / 4.5, (j - 2) * d / 6
            b.box((x, y + 0.0012, z), (tile, 0.0004, tile), color, PLAIN, faces="+y")


def build_tablet(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tablet lying flat with its screen on, or propped up on a folding stand."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, t = 0.17 * s, 0.24 * s, 0.008 * s
    tablet = MeshBuilder()
    tablet.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    _screen(tablet, w * 0.88, d * 0.88, t, rng)
    mesh = tablet.build()
    if style.shape == "flat":
        return ObjectModel(mesh)
    propped = rotated_about_x(mesh, -math.radians(65.0))  # leaning back, screen to the front
    stand = MeshBuilder()
    foot = shade(color, 0.7)
    stand.box((0.0, 0.004 * s, 0.0), (w * 0.6, 0.008 * s, 0.11 * s), foot, mat)
    beam(stand, (0.0, 0.0, -0.05 * s), (0.0, 0.12 * s, -0.01 * s), w * 0.4, 0.008 * s, foot, mat)
    return ObjectModel(standing_on_floor(Mesh.concatenate([propped, stand.build()])))


def build_remote_control(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A long remote lying flat: a red power button, arrow pad and rows of buttons."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    slim = style.shape == "slim"
    w, t = (0.04 if slim else 0.05) * s, (0.014 if slim else 0.022) * s
    d = float(rng.uniform(0.17, 0.2)) * s
    b = MeshBuilder()
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    keys = _keys_color(color)
    b.box((0.0, t + 0.002, -d * 0.4), (0.01 * s, 0.004, 0.01 * s), color_rgb("red"), PLASTIC)
    ring(
        b,
        (0.0, t + 0.002, -d * 0.15),
        0.016 * s,
        0.007 * s,
        0.004,
        keys,
        PLASTIC,
        axis="y",
        segments=8,
    )
    _buttons(b, (0.0, t, d * 0.2), (3, 2 if slim else 4), 0.013 * s, 0.008 * s, keys)
    return ObjectModel(b.build())


def build_mouse(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A computer mouse with a scroll wheel, on a mouse pad, with a cable if it is wired."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    pad = 0.003 * s
    b.box(
        (0.0, pad / 2, 0.0),
        (0.22 * s, pad, 0.18 * s),
        color_rgb("dark gray"),
        material_index("fabric"),
    )
    length = float(rng.uniform(0.1, 0.115)) * s
    b.sphere(
        (0.0, pad, 0.0),
        1.0,
        color,
        mat,
        segments=10,
        scale=(0.031 * s, 0.036 * s, length / 2),
        upper_half_only=True,
    )
    b.box(
        (0.0, pad + 0.03 * s, -length * 0.22),
        (0.001, 0.012 * s, length * 0.35),
        shade(color, 0.4),
        mat,
    )
    b.cylinder(
        (-0.004 * s, pad + 0.035 * s, -length * 0.22),
        0.006 * s,
        0.008 * s,
        shade(color, 0.5),
        PLASTIC,
        segments=6,
        axis="x",
    )
    if style.shape == "wired":
        cable = color_rgb("black") if style.color != "black" else color_rgb("gray")
        beam(
            b,
            (0.0, pad + 0.003, -length / 2),
            (0.02 * s, pad + 0.003, -0.09 * s),
            0.004,
            0.004,
            cable,
            PLASTIC,
        )
    return ObjectModel(b.build())


def build_radio(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A portable radio with a speaker grille, tuning dial and aerial, or a wooden retro set."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    w, h, d = 0.26 * s, 0.15 * s, 0.08 * s
    grille = color_rgb("dark gray")
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    if style.shape == "retro":
        b.cylinder((-w / 2, h, 0.0), d / 2, w, color, mat, segments=8, axis="x")
        b.box(
            (-w * 0.18, h * 0.5, d / 2 + 0.001),
            (w * 0.5, h * 0.7, 0.002),
            color_rgb("beige"),
            material_index("fabric"),
        )
        b.box(
            (w * 0.28, h * 0.65, d / 2 + 0.001),
            (w * 0.3, h * 0.15, 0.002),
            color_rgb("cream"),
            PLAIN,
        )
    else:
        b.cylinder(
            (-w * 0.2, h * 0.5, d / 2), h * 0.35, 0.004 * s, grille, PLASTIC, segments=12, axis="z"
        )
        b.box(
            (w * 0.25, h * 0.65, d / 2 + 0.001),
            (w * 0.35, h * 0.2, 0.002),
            color_rgb("light blue"),
            GLASS,
        )
        ring(
            b,
            (0.0, h, 0.0),
            w * 0.35,
            0.012 * s,
            0.02 * s,
            shade(color, 0.5),
            mat,
            segments=8,
            arc=(0.0, math.pi),
        )
        tilt = float(rng.uniform(0.2, 0.5))
        tip = (w * 0.45 - 0.15 * s * math.sin(tilt), h + 0.15 * s * math.cos(tilt), -d * 0.3)
        beam(b, (w * 0.45, h, -d * 0.3), tip, 0.004 * s, 0.004 * s, color_rgb("silver"), METAL)
    for x in (w * 0.18, w * 0.36):
        b.cylinder(
            (x, h * 0.28, d / 2),
            0.012 * s,
            0.01 * s,
            shade(color, 0.5),
            PLASTIC,
            segments=8,
            axis="z",
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="telephone",
        shapes={"desk": "desk telephone", "cordless": "cordless telephone"},
        colors=GADGET_COLORS,
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.25, "living room": 0.15, "corridor": 0.1, "bedroom": 0.05},
        build=build_telephone,
    ),
    Category(
        name="camera",
        shapes={"digital": "digital camera", "professional": "professional camera"},
        colors=("black", "silver", "gray", "white", "red", "dark gray"),
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.12, "living room": 0.08, "bedroom": 0.05},
        build=build_camera,
    ),
    Category(
        name="tablet",
        shapes={"flat": "tablet lying flat", "stand": "tablet on a stand"},
        colors=("black", "silver", "white", "gray", "gold", "pink"),
        materials=("metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.15, "bedroom": 0.15, "study": 0.15},
        build=build_tablet,
    ),
    Category(
        name="remote control",
        shapes={"tv": "tv remote control", "slim": "slim remote control"},
        colors=("black", "gray", "silver", "white", "dark gray"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.6, "bedroom": 0.15},
        build=build_remote_control,
    ),
    Category(
        name="mouse",
        shapes={"wired": "wired mouse", "wireless": "wireless mouse"},
        colors=("black", "white", "gray", "silver", "red", "blue"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.6, "bedroom": 0.05},
        build=build_mouse,
    ),
    Category(
        name="radio",
        shapes={"portable": "portable radio", "retro": "retro radio"},
        colors=("black", "silver", "red", "brown", "cream", "blue", "gray"),
        materials=("plastic", "wood", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.15, "living room": 0.1, "study": 0.1, "bedroom": 0.05},
        build=build_radio,
    ),
]
