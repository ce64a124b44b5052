"""Food and drink on counters and tables: bread, cans, jars and wine.

Every model stands on a surface and fits a 0.4 x 0.3 m footprint at the largest scale. Wine's
colour is the colour of the wine, which shows in the glass, the carafe or the bottles.
"""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.parts import beam, shade, standing_on_floor
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

PLAIN = material_index("plain")
METAL = material_index("metal")
GLASS = material_index("glass")
WOOD = material_index("wood")
SILVER = color_rgb("silver")
CRUMB = color_rgb("cream")
LABEL_COLORS = ("red", "blue", "green", "yellow", "white", "orange", "black", "silver", "purple")


def build_bread(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An oval loaf, a tin loaf cut into leaning slices, or a scored baguette."""
    s = style.scale
    crust, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "baguette":
        length = float(rng.uniform(0.3, 0.34)) * s
        r = 0.03 * s
        b.sphere((0.0, r, 0.0), 1.0, crust, mat, segments=10, scale=(length / 2, r, r * 1.1))
        for k in range(4):
            x = (k - 1.5) * length * 0.2
            beam(
                b,
                (x - 0.02 * s, r * 1.93, -0.012 * s),
                (x + 0.02 * s, r * 1.93, 0.012 * s),
                0.006 * s,
                0.004 * s,
                shade(crust, 1.5),
                mat,
            )
        return ObjectModel(b.build())
    w, d, h = 0.22 * s, 0.11 * s, 0.045 * s
    if style.shape == "loaf":
        b.sphere(
            (0.0, 0.045 * s, 0.0), 1.0, crust, mat, segments=12, scale=(w / 2, 0.045 * s, d / 2)
        )
        return ObjectModel(standing_on_floor(b.build()))
    length = w * 0.6
    x0 = (w - length) / 2
    b.box((x0, h / 2, 0.0), (length, h, d), crust, mat)
    dome = (length / 2 * 1.2, 0.045 * s, d / 2 * 1.25)
    b.sphere((x0, h, 0.0), 1.0, crust, mat, segments=10, scale=dome, upper_half_only=True)
    cut, top = x0 - length / 2 - 0.0005, h + 0.045 * s
    b.box((cut, h / 2, 0.0), (0.001, h * 0.9, d * 0.9), CRUMB, PLAIN, faces="-x")
    b.sphere(
        (cut, h, 0.0),
        1.0,
        CRUMB,
        PLAIN,
        segments=10,
        scale=(0.001, 0.05 * s, d * 0.45),
        upper_half_only=True,
    )
    for k in range(3):
        x = x0 - length / 2 - 0.016 * s * (k + 1)
        lean = 0.012 * s * (k + 1)
        crust_at = (x - lean, top * 0.88, 0.0)
        beam(b, (x, 0.0, 0.0), crust_at, d * 0.95, 0.012 * s, CRUMB, PLAIN, side=(0.0, 0.0, 1.0))
        beam(
            b,
            crust_at,
            (x - lean * 1.12, top, 0.0),
            d * 0.85,
            0.013 * s,
            crust,
            mat,
            side=(0.0, 0.0, 1.0),
        )
    return ObjectModel(standing_on_floor(b.build()))


def _can(b: MeshBuilder, y: float, r: float, h: float, label: Rgb, mat: int) -> None:
    """A metal can standing at height ``y``, its label band between silver rims."""
    b.cylinder((0.0, y, 0.0), r * 0.96, 0.006, SILVER, METAL, segments=10)
    b.cylinder((0.0, y + 0.006, 0.0), r, h - 0.012, label, mat, segments=10)
    b.cylinder((0.0, y + h - 0.006, 0.0), r * 0.96, 0.006, SILVER, METAL, segments=10)


def build_can(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A soda can with a pull tab, or squat food cans with paper labels, one or two stacked."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    white = color_rgb("white")
    b = MeshBuilder()
    if style.shape == "soda":
        h, r = 0.122 * s, 0.033 * s
        _can(b, 0.0, r, h, color, mat)
        b.cylinder((0.0, h - 0.006, 0.0), r * 0.8, 0.003 * s, SILVER, METAL, segments=10)
        b.box((0.006 * s, h - 0.002 * s, 0.0), (0.018 * s, 0.002 * s, 0.01 * s), SILVER, METAL)
        b.box((0.0, h * 0.55, r + 0.0005), (r * 0.9, h * 0.3, 0.001), white, mat, faces="+z")
        return ObjectModel(b.build())
    h, r = 0.1 * s, 0.042 * s
    for k in range(int(rng.integers(1, 3))):
        _can(b, k * h, r, h, color, mat)
        b.cylinder(
            (0.0, k * h + h * 0.3, 0.0), r + 0.0008, h * 0.4, white, PLAIN, segments=10, caps=False
        )
    return ObjectModel(b.build())


def build_jar(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A mason jar with a screw lid, a round cookie jar with a knob, or a tall storage jar."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "cookie":
        r = 0.075 * s
        b.sphere((0.0, r, 0.0), 1.0, color, mat, segments=12, scale=(r, r, r))
        b.cylinder((0.0, r * 1.75, 0.0), r * 0.6, 0.02 * s, shade(color, 0.85), mat, segments=10)
        b.sphere((0.0, r * 1.75 + 0.03 * s, 0.0), 0.014 * s, shade(color, 0.7), mat, segments=6)
        return ObjectModel(b.build())
    tall = style.shape == "storage"
    r = (0.05 if tall else 0.04) * s
    h = float(rng.uniform(0.2, 0.24) if tall else rng.uniform(0.11, 0.13)) * s
    b.cylinder((0.0, 0.0, 0.0), r, h, color, mat, segments=10)
    if not tall:  # the threaded neck under the screw lid
        b.cylinder((0.0, h, 0.0), r * 0.85, 0.006 * s, shade(color, 0.8), mat, segments=10)
    lid = color_rgb("gold") if not tall else color_rgb("brown")
    lid_y = h if tall else h + 0.006 * s
    b.cylinder((0.0, lid_y, 0.0), r * 1.02, 0.02 * s, lid, WOOD if tall else METAL, segments=10)
    return ObjectModel(b.build())


def build_wine(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A stemmed glass of wine, a decanter of wine, or a small rack of wine bottles."""
    s = style.scale
    wine, mat = color_rgb(style.color), material_index(style.material)
    clear = color_rgb("light gray")
    b = MeshBuilder()
    if style.shape == "glass":
        b.cylinder((0.0, 0.0, 0.0), 0.035 * s, 0.004 * s, clear, mat, segments=10)
        b.cylinder((0.0, 0.004 * s, 0.0), 0.005 * s, 0.08 * s, clear, mat, segments=6)
        b.cylinder(
            (0.0, 0.084 * s, 0.0), 0.02 * s, 0.045 * s, wine, mat, segments=10, radius_top=0.038 * s
        )
        b.cylinder(
            (0.0, 0.129 * s, 0.0),
            0.038 * s,
            0.05 * s,
            clear,
            mat,
            segments=10,
            radius_top=0.034 * s,
            caps=False,
        )
        b.cylinder((0.0, 0.129 * s, 0.0), 0.035 * s, 0.001, shade(wine, 0.7), mat, segments=10)
        return ObjectModel(b.build())
    if style.shape == "decanter":
        b.cylinder((0.0, 0.0, 0.0), 0.09 * s, 0.07 * s, wine, mat, segments=12, radius_top=0.06 * s)
        b.cylinder(
            (0.0, 0.07 * s, 0.0), 0.06 * s, 0.05 * s, clear, mat, segments=12, radius_top=0.022 * s
        )
        b.cylinder(
            (0.0, 0.12 * s, 0.0), 0.022 * s, 0.1 * s, clear, mat, segments=10, radius_top=0.028 * s
        )
        return ObjectModel(b.build())
    w, d = 0.3 * s, 0.2 * s
    frame = color_rgb("brown")
    n = int(rng.integers(2, 4))
    for x in (-w / 2, w / 2):
        for z in (-d / 2, d / 2):
            b.box((x, 0.09 * s, z), (0.015 * s, 0.18 * s, 0.015 * s), frame, WOOD)
    for y in (0.02 * s, 0.1 * s):
        for z in (-d / 2, d / 2):
            b.box((0.0, y, z), (w, 0.015 * s, 0.015 * s), frame, WOOD)
    r = 0.034 * s
    for k in range(2 * n):
        y = 0.027 * s + r + (k // n) * 0.08 * s
        z = ((k % n) - (n - 1) / 2) * (d * 0.9 / n)
        b.cylinder((-w * 0.45, y, z), r, w * 0.6, wine, mat, segments=6, axis="x")
        neck = (w * 0.15, y, z)
        b.cylinder(neck, r, 0.1 * s, wine, mat, segments=6, radius_top=0.012 * s, axis="x")
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="bread",
        shapes={"loaf": "loaf of bread", "sliced": "sliced loaf of bread", "baguette": "baguette"},
        colors=("brown", "beige", "dark brown", "orange"),
        materials=("plain",),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.3, "dining room": 0.15},
        build=build_bread,
    ),
    Category(
        name="can",
        shapes={"soda": "soda can", "food": "food can"},
        colors=LABEL_COLORS,
        materials=("metal",),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.3, "storage room": 0.3, "living room": 0.08},
        build=build_can,
    ),
    Category(
        name="jar",
        shapes={"mason": "mason jar", "cookie": "cookie jar", "storage": "storage jar"},
        colors=("white", "light gray", "cream", "light blue", "green", "brown", "red"),
        materials=("glass", "ceramic"),
        placement=Placement.ON_SURFACE,
        rooms={"kitchen": 0.4, "storage room": 0.2, "living room": 0.05},
        build=build_jar,
    ),
    Category(
        name="wine",
        shapes={"glass": "glass of wine", "decanter": "wine decanter", "rack": "wine rack"},
        colors=("red", "dark brown", "purple", "pink", "yellow"),
        materials=("glass",),
        placement=Placement.ON_SURFACE,
        rooms={"dining room": 0.3, "kitchen": 0.2, "living room": 0.15},
        build=build_wine,
    ),
]
