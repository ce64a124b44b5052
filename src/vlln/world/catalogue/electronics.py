"""Screens, computers, audio and other plugged-in things (the fan lives here too)."""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, ring, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

DEVICE_COLORS = ("black", "white", "gray", "silver")

GLASS = material_index("glass")
PLASTIC = material_index("plastic")
METAL = material_index("metal")
BLACK = color_rgb("black")
SCREEN = (0.03, 0.04, 0.07)  # a switched-off panel: black with a faint blue


def build_tv(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A thin dark panel in a bezel, on a central pedestal or on two feet."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w = float(rng.uniform(0.95, 1.25)) * s
    h, t, lift = w * 0.58, 0.05 * s, 0.09 * s
    b = MeshBuilder()
    b.box((0.0, lift + h / 2, 0.0), (w, h, t), color, mat)
    b.box((0.0, lift + h / 2, t / 2 + 0.002), (w - 0.03, h - 0.03, 0.004), SCREEN, GLASS)
    if style.shape == "pedestal":
        b.box((0.0, lift / 2, -0.01), (0.06 * s, lift, 0.03 * s), color, mat)
        b.box((0.0, 0.006, 0.0), (0.4 * s, 0.012, 0.22 * s), color, mat)
    else:
        for x in (-1, 1):
            foot_x = x * (w / 2 - 0.08 * s)
            for k in (-1, 1):
                beam(
                    b,
                    (foot_x, lift + 0.02, 0.0),
                    (foot_x + x * 0.03, 0.005, k * 0.1 * s),
                    0.025 * s,
                    0.01,
                    color,
                    METAL,
                    side=(1.0, 0.0, 0.0),
                )
    return ObjectModel(b.build())


def build_computer_monitor(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A screen on a neck and a foot; the curved one is bent from five panels."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w = float(rng.uniform(0.5, 0.6)) * s * (1.25 if style.shape == "curved" else 1.0)
    h, t, lift = 0.32 * s, 0.025 * s, 0.11 * s
    b = MeshBuilder()
    if style.shape == "curved":
        n, bend = 5, 0.35  # radians of arc across the screen
        radius = w / bend
        for k in range(n):
            a = (k - (n - 1) / 2) * bend / n
            x, z = radius * math.sin(a), radius * (1.0 - math.cos(a))
            seg = 2 * radius * math.sin(bend / n / 2) + 0.002
            b.box((x, lift + h / 2, z), (seg, h, t), color, mat, yaw=-a)
            fx, fz = x + (t / 2 + 0.002) * -math.sin(a), z + (t / 2 + 0.002) * math.cos(a)
            b.box((fx, lift + h / 2, fz), (seg, h - 0.02, 0.002), SCREEN, GLASS, yaw=-a)
    else:
        b.box((0.0, lift + h / 2, 0.0), (w, h, t), color, mat)
        b.box((0.0, lift + h / 2, t / 2 + 0.002), (w - 0.02, h - 0.02, 0.004), SCREEN, GLASS)
    b.box((0.0, (lift + h * 0.4) / 2, -t / 2 - 0.015), (0.05 * s, lift + h * 0.4, 0.03), color, mat)
    b.box((0.0, 0.005, -0.02), (0.24 * s, 0.01, 0.18 * s), color, mat)
    return ObjectModel(b.build())


def build_laptop(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A thin base with keyboard and touchpad and, when open, a lid tilted back."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, t = 0.32 * s, 0.2 * s, 0.016 * s
    b = MeshBuilder()
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    if style.shape == "closed":
        b.box((0.0, t + 0.004, 0.0), (w, 0.008, d), shade(color, 0.9), mat)
        b.box(
            (0.0, t + 0.0085, 0.0),
            (0.03 * s, 0.001, 0.03 * s),
            color_rgb("silver"),
            METAL,
            faces="+y",
        )
        return ObjectModel(b.build())
    b.box((0.0, t + 0.0005, -0.02 * s), (w * 0.85, 0.001, d * 0.45), BLACK, PLASTIC, faces="+y")
    b.box(
        (0.0, t + 0.0005, d * 0.33),
        (w * 0.3, 0.001, d * 0.2),
        shade(color, 0.8),
        PLASTIC,
        faces="+y",
    )
    tilt = math.radians(float(rng.uniform(6.0, 14.0)))
    along = np.array([0.0, math.cos(tilt), -math.sin(tilt)])
    front = np.array([0.0, math.sin(tilt), math.cos(tilt)])
    hinge = np.array([0.0, t, -d / 2 + 0.004])
    length = 0.2 * s
    beam(b, _v(hinge), _v(hinge + along * length), w, 0.007, shade(color, 0.9), mat)
    glass0 = hinge + front * 0.004 + along * 0.012
    beam(b, _v(glass0), _v(glass0 + along * (length - 0.024)), w - 0.024, 0.002, SCREEN, GLASS)
    return ObjectModel(b.build())


def _v(a: np.ndarray) -> tuple[float, float, float]:
    return (float(a[0]), float(a[1]), float(a[2]))


def build_keyboard(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A low slab with rows of raised keys and a long space bar."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    cols = 13 if style.shape == "standard" else 10
    key = 0.0235 * s
    w, d, t = (cols * key + 0.02 * s), 5 * key + 0.02 * s, 0.018 * s
    key_color = shade(color, 0.7) if style.color != "black" else color_rgb("dark gray")
    b = MeshBuilder()
    b.box((0.0, t / 2, 0.0), (w, t, d), color, mat)
    for row in range(4):
        z = -d / 2 + 0.01 * s + key * (row + 0.5)
        for col in range(cols):
            x = -w / 2 + 0.01 * s + key * (col + 0.5)
            b.box(
                (x, t + 0.004, z), (key * 0.82, 0.008, key * 0.82), key_color, PLASTIC, faces="+y+z"
            )
    z = -d / 2 + 0.01 * s + key * 4.5
    b.box((0.0, t + 0.004, z), (key * 5.5, 0.008, key * 0.82), key_color, PLASTIC, faces="+y+z")
    return ObjectModel(b.build())


def build_printer(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A boxy body with a paper tray: sheets standing at the back (inkjet) or a top output."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    laser = style.shape == "laser"
    w, d = 0.34 * s, 0.2 * s
    h = (0.22 if laser else 0.14) * s + float(rng.uniform(0.0, 0.02)) * s
    paper = color_rgb("white")
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    b.box((0.0, h * 0.35, d / 2 + 0.015 * s), (w * 0.6, 0.008, 0.03 * s), shade(color, 0.8), mat)
    b.box((0.0, h * 0.5, d / 2 + 0.001), (w * 0.62, 0.012, 0.002), BLACK, PLASTIC, faces="+z")
    b.box((w * 0.3, h + 0.001, d * 0.3), (w * 0.18, 0.002, d * 0.18), BLACK, GLASS, faces="+y")
    if laser:
        b.box(
            (-0.02 * s, h + 0.001, -0.01),
            (w * 0.55, 0.002, d * 0.6),
            shade(color, 0.5),
            mat,
            faces="+y",
        )
    else:
        top, back = (0.0, h, -d / 2 + 0.01), (0.0, h + 0.12 * s, -d / 2 - 0.015 * s)
        beam(b, top, back, w * 0.7, 0.006, shade(color, 0.85), mat)
        beam(
            b,
            (0.0, h + 0.004, -d / 2 + 0.02),
            (0.0, h + 0.1 * s, -d / 2 - 0.005 * s),
            w * 0.55,
            0.004,
            paper,
            material_index("plain"),
        )
    return ObjectModel(b.build())


def build_speaker(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A box with a woofer and a tweeter, or a cylindrical smart speaker with a light ring."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    dark = shade(color, 0.35)
    b = MeshBuilder()
    if style.shape == "smart":
        r, h = 0.055 * s, (0.15 + float(rng.uniform(0.0, 0.05))) * s
        b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=12)
        b.cylinder((0.0, h, 0.0), r * 0.85, 0.004, dark, PLASTIC, segments=12)
        ring(
            b,
            (0.0, h + 0.003, 0.0),
            r * 0.7,
            0.008,
            0.003,
            color_rgb("light blue"),
            PLASTIC,
            axis="y",
            segments=10,
        )
        return ObjectModel(b.build())
    w, d = 0.16 * s, 0.2 * s
    h = (0.26 + float(rng.uniform(0.0, 0.06))) * s
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    for y, r in ((h * 0.35, w * 0.38), (h * 0.78, w * 0.15)):
        ring(b, (0.0, y, zf + 0.004), r, 0.012 * s, 0.008, BLACK, PLASTIC, segments=10)
        b.cylinder((0.0, y, zf), r - 0.012 * s, 0.004, dark, PLASTIC, segments=10, axis="z")
    return ObjectModel(b.build())


def build_game_console(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A slab lying down or standing up, with a power light and a controller beside it."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "vertical":
        w, h, d = 0.08 * s, 0.28 * s, 0.22 * s
        b.box((0.0, 0.005, 0.0), (w * 1.6, 0.01, d * 0.6), BLACK, PLASTIC)
        b.box((0.0, 0.01 + h / 2, 0.0), (w, h, d), color, mat)
        b.box(
            (0.0, 0.01 + h * 0.85, d / 2 + 0.001),
            (w * 0.2, 0.01, 0.002),
            color_rgb("light blue"),
            PLASTIC,
            faces="+z",
        )
        pad_x = w + 0.06 * s
    else:
        w, h, d = 0.28 * s, 0.06 * s, 0.22 * s
        b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
        b.box((0.0, h + 0.003, 0.0), (w * 0.96, 0.006, d * 0.96), shade(color, 0.8), mat)
        b.box(
            (w * 0.35, h * 0.5, d / 2 + 0.001),
            (0.01, 0.01, 0.002),
            color_rgb("light blue"),
            PLASTIC,
            faces="+z",
        )
        pad_x = 0.0
    pad_y = 0.025 * s + (0.0 if pad_x else h + 0.006)
    pad = BLACK if style.color != "black" else color_rgb("dark gray")
    b.sphere((pad_x, pad_y, d * 0.15), 0.06 * s, pad, PLASTIC, segments=8, scale=(1.0, 0.3, 0.6))
    for k in (-1, 1):
        b.sphere((pad_x + k * 0.045 * s, pad_y, d * 0.22), 0.025 * s, pad, PLASTIC, segments=6)
    return ObjectModel(b.build())


def build_fan(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A pedestal fan (base, pole, motor, blades in a round guard) or a grilled tower fan."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "tower":
        h = float(rng.uniform(0.8, 1.0)) * s
        b.cylinder((0.0, 0.0, 0.0), 0.15 * s, 0.04 * s, color, mat, segments=12)
        b.cylinder((0.0, 0.04 * s, 0.0), 0.07 * s, h, color, mat, segments=10)
        b.box(
            (0.0, 0.04 * s + h * 0.55, 0.06 * s),
            (0.06 * s, h * 0.7, 0.03 * s),
            shade(color, 0.3),
            PLASTIC,
        )
        return ObjectModel(b.build())
    h = float(rng.uniform(1.0, 1.25)) * s
    b.cylinder((0.0, 0.0, 0.0), 0.18 * s, 0.03 * s, color, mat, segments=12)
    b.cylinder((0.0, 0.03 * s, 0.0), 0.015 * s, h - 0.03 * s, color, mat, segments=8)
    r = 0.2 * s
    cy = h + r - 0.05 * s
    b.cylinder((0.0, cy, -0.1 * s), 0.06 * s, 0.1 * s, color, mat, segments=10, axis="z")
    b.cylinder((0.0, cy, 0.0), 0.03 * s, 0.04 * s, shade(color, 0.8), mat, segments=8, axis="z")
    for k in range(3):
        a = 2 * math.pi * k / 3 + float(rng.uniform(0.0, 1.0))
        tip = (r * 0.85 * math.cos(a), cy + r * 0.85 * math.sin(a), 0.03 * s)
        beam(
            b,
            (0.0, cy, 0.03 * s),
            tip,
            0.09 * s,
            0.004,
            shade(color, 0.9),
            PLASTIC,
            side=(-math.sin(a), math.cos(a), 0.0),
        )
    guard = color_rgb("silver") if style.color in ("black", "blue") else shade(color, 0.7)
    ring(b, (0.0, cy, 0.035 * s), r, 0.012, 0.1 * s, guard, METAL, segments=14)
    b.box((0.0, cy, 0.085 * s), (2 * r - 0.01, 0.006, 0.006), guard, METAL, faces="+z+y")
    b.box((0.0, cy, 0.085 * s), (0.006, 2 * r - 0.01, 0.006), guard, METAL, faces="+z+x")
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="tv",
        shapes={"pedestal": "flat-screen tv", "feet": "flat-screen tv on feet"},
        colors=("black", "dark gray", "silver", "white"),
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.9, "bedroom": 0.3, "gym": 0.1, "kitchen": 0.05},
        build=build_tv,
    ),
    Category(
        name="computer monitor",
        shapes={"flat": "computer monitor", "curved": "curved monitor"},
        colors=DEVICE_COLORS,
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 1.0, "bedroom": 0.25, "living room": 0.05},
        build=build_computer_monitor,
    ),
    Category(
        name="laptop",
        shapes={"open": "open laptop", "closed": "closed laptop"},
        colors=DEVICE_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.5, "bedroom": 0.3, "living room": 0.3, "dining room": 0.1},
        build=build_laptop,
    ),
    Category(
        name="keyboard",
        shapes={"standard": "computer keyboard", "compact": "compact keyboard"},
        colors=DEVICE_COLORS,
        materials=("plastic", "metal"),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.8, "bedroom": 0.15},
        build=build_keyboard,
    ),
    Category(
        name="printer",
        shapes={"inkjet": "inkjet printer", "laser": "laser printer"},
        colors=("white", "black", "gray"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"study": 0.4, "corridor": 0.02, "living room": 0.03},
        build=build_printer,
    ),
    Category(
        name="speaker",
        shapes={"bookshelf": "bookshelf speaker", "smart": "smart speaker"},
        colors=("black", "white", "brown", "dark brown", "gray"),
        materials=("wood", "plastic", "fabric"),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.6, "study": 0.3, "bedroom": 0.3, "gym": 0.3, "kitchen": 0.1},
        build=build_speaker,
    ),
    Category(
        name="game console",
        shapes={"horizontal": "game console", "vertical": "upright game console"},
        colors=("black", "white", "gray"),
        materials=("plastic",),
        placement=Placement.ON_SURFACE,
        rooms={"living room": 0.35, "bedroom": 0.15},
        build=build_game_console,
    ),
    Category(
        name="fan",
        shapes={"pedestal": "pedestal fan", "tower": "tower fan"},
        colors=("white", "black", "gray", "blue"),
        materials=("plastic", "metal"),
        placement=Placement.CORNER,
        rooms={"bedroom": 0.15, "living room": 0.15, "study": 0.2, "gym": 0.25},
        build=build_fan,
    ),
]
