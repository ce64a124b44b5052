"""More household machines: ovens, range hoods, dryers, air conditioners, water coolers and
water heaters.

Wall-mounted ones (the range hood, the split air conditioner) have their back on z = 0 and
their bottom on y = 0; ``wall_height`` lifts them to where they hang.
"""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.parts import facing_polygon, ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

APPLIANCE_COLORS = ("white", "silver", "black", "gray", "cream")
METAL = material_index("metal")
GLASS = material_index("glass")
PLASTIC = material_index("plastic")
BLACK = color_rgb("black")
DARK = color_rgb("dark gray")
SILVER = color_rgb("silver")


def _oven_door(
    b: MeshBuilder, w: float, y: float, h: float, z: float, color: Rgb, s: float
) -> None:
    """A door with a dark glass window and a bar handle along its top, on the face ``z``."""
    b.box((0.0, y + h / 2, z + 0.01), (w * 0.94, h - 0.01, 0.02), shade(color, 0.92), METAL)
    b.box((0.0, y + h * 0.45, z + 0.021), (w * 0.7, h * 0.55, 0.004), BLACK, GLASS, faces="+z")
    b.box((0.0, y + h - 0.05 * s, z + 0.05), (w * 0.75, 0.02, 0.02), SILVER, METAL)
    for k in (-1, 1):
        b.box((k * w * 0.3, y + h - 0.05 * s, z + 0.035), (0.015, 0.015, 0.03), SILVER, METAL)


def build_oven(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall oven housing: one or two oven doors with windows, a control strip, a drawer."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    double = style.shape == "double"
    w, d, h = 0.6 * s, 0.58 * s, (1.5 if double else 1.2) * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    y = 0.08 * s
    b.box((0.0, y + 0.15 * s, zf + 0.01), (w * 0.94, 0.28 * s, 0.02), shade(color, 1.08), mat)
    b.box((0.0, y + 0.25 * s, zf + 0.03), (0.18 * s, 0.015, 0.02), SILVER, METAL)
    y += 0.32 * s
    for _ in range(2 if double else 1):
        _oven_door(b, w, y, 0.46 * s, zf, color, s)
        y += 0.5 * s
    b.box((0.0, y + 0.05 * s, zf + 0.004), (w * 0.94, 0.08 * s, 0.008), BLACK, GLASS)
    n = 2 + int(rng.integers(0, 2))
    for k in range(n):
        x = (k - (n - 1) / 2) * 0.12 * s
        b.cylinder((x, y + 0.05 * s, zf), 0.018 * s, 0.02, SILVER, METAL, segments=8, axis="z")
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_range_hood(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A sloping canopy under a chimney stack (chimney), or a flat slab hood with a visor."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w = float(rng.choice([0.6, 0.75, 0.9])) * s
    d = 0.48 * s
    b = MeshBuilder()
    b.box((0.0, 0.03 * s, d / 2), (w, 0.06 * s, d), color, mat)
    b.box((0.0, 0.0005, d / 2), (w * 0.8, 0.001, d * 0.7), DARK, METAL, faces="-y")
    if style.shape == "flat":
        b.box((0.0, 0.12 * s, 0.14 * s), (w, 0.12 * s, 0.28 * s), color, mat)
        b.box((0.0, 0.07 * s, d + 0.005), (w * 0.9, 0.02, 0.01), BLACK, GLASS, faces="+z+y-y")
        return ObjectModel(b.build())
    top_y, canopy_d, stack_w = 0.3 * s, 0.22 * s, 0.28 * s
    front = np.array  # a point or direction
    for sx in (-1.0, 1.0):  # the sides: trapezoids from the canopy's edge to the stack
        corners = [
            front([sx * w / 2, 0.06 * s, 0.0]),
            front([sx * w / 2, 0.06 * s, d]),
            front([sx * stack_w / 2, top_y, canopy_d]),
            front([sx * stack_w / 2, top_y, 0.0]),
        ]
        facing_polygon(b, corners, front([sx, 0.3, 0.0]), color, mat)
    slope = [
        front([-w / 2, 0.06 * s, d]),
        front([w / 2, 0.06 * s, d]),
        front([stack_w / 2, top_y, canopy_d]),
        front([-stack_w / 2, top_y, canopy_d]),
    ]
    facing_polygon(b, slope, front([0.0, 0.6, 1.0]), shade(color, 1.06), mat)
    stack_h = 0.5 * s
    b.box((0.0, top_y + stack_h / 2, canopy_d / 2), (stack_w, stack_h, canopy_d), color, mat)
    b.box((0.0, 0.035 * s, d + 0.003), (w * 0.5, 0.025 * s, 0.006), BLACK, GLASS, faces="+z")
    return ObjectModel(b.build())


def build_clothes_dryer(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A cube with a large round door of tinted glass, a control panel and a lint drawer."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d = 0.6 * s, 0.6 * s
    h = (0.85 if style.shape == "front-loading" else 0.7) * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    door_y, r = h * 0.47, 0.2 * s
    ring(b, (0.0, door_y, zf + 0.02), r, 0.03 * s, 0.04, SILVER, METAL, segments=14)
    b.cylinder((0.0, door_y, zf), r - 0.03 * s, 0.025, DARK, GLASS, segments=14, axis="z")
    panel_y = h - 0.06 * s
    b.box((0.0, panel_y, zf + 0.004), (w - 0.02, 0.09 * s, 0.008), shade(color, 0.85), mat)
    b.box((-w * 0.3, panel_y, zf + 0.01), (0.12 * s, 0.05 * s, 0.01), BLACK, GLASS)
    knob_x = w * float(rng.choice([0.15, 0.3]))
    b.cylinder((knob_x, panel_y, zf), 0.028 * s, 0.03, SILVER, METAL, segments=10, axis="z")
    b.box((0.0, 0.06 * s, zf + 0.004), (w * 0.9, 0.05 * s, 0.008), shade(color, 0.8), mat)
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_air_conditioner(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A split unit on the wall: a long rounded box with a louvre along its bottom; the slim
    one is wider and flatter with a display."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    slim = style.shape == "slim"
    w = float(rng.uniform(0.8, 0.95)) * s * (1.15 if slim else 1.0)
    h, d = (0.26 if slim else 0.3) * s, (0.18 if slim else 0.23) * s
    b = MeshBuilder()
    b.box((0.0, h / 2, d / 2), (w - d, h, d), color, mat)
    for x in (-(w - d) / 2, (w - d) / 2):  # rounded ends
        b.cylinder((x, 0.0, d / 2), d / 2, h, color, mat, segments=10)
    b.box((0.0, 0.06 * s, d + 0.002), (w * 0.9, 0.035 * s, 0.004), DARK, PLASTIC, faces="+z")
    for k in range(4 if slim else 6):
        y = h * (0.4 + 0.08 * k)
        b.box((0.0, y, d + 0.001), (w * 0.94, 0.004, 0.002), shade(color, 0.85), mat, faces="+z")
    light = color_rgb("blue") if slim else color_rgb("green")
    b.box((w * 0.36, h * 0.75, d + 0.003), (0.05 * s, 0.015, 0.004), light, GLASS)
    return ObjectModel(b.build())


def build_water_cooler(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A cabinet with two taps over a drip tray, an upturned blue water bottle on top."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, h = 0.32 * s, 0.32 * s, 0.95 * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    b.box(
        (0.0, h * 0.68, zf + 0.02), (w * 0.8, h * 0.2, 0.04), shade(color, 0.8), mat, faces="+z+x-x"
    )
    for x, tap in ((-w * 0.2, color_rgb("blue")), (w * 0.2, color_rgb("red"))):
        b.box((x, h * 0.74, zf + 0.05), (0.035 * s, 0.05 * s, 0.04 * s), tap, PLASTIC)
    b.box((0.0, h * 0.55, zf + 0.03), (w * 0.7, 0.02 * s, 0.06 * s), DARK, PLASTIC)
    water = (0.45, 0.68, 0.92)
    bottle_r = 0.13 * s
    b.cylinder((0.0, h, 0.0), 0.05 * s, 0.04 * s, water, PLASTIC, segments=10)
    b.cylinder((0.0, h + 0.04 * s, 0.0), 0.05 * s, 0.05 * s, water, PLASTIC, 10, bottle_r)
    fill = float(rng.uniform(0.15, 0.3)) * s
    b.cylinder((0.0, h + 0.09 * s, 0.0), bottle_r, fill, water, PLASTIC, segments=12)
    return ObjectModel(b.build())


def build_water_heater(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall insulated tank with pipes and a valve (tank), or a boiler box on the wall."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    copper = color_rgb("orange")
    if style.shape == "tank":
        r, h = float(rng.uniform(0.24, 0.3)) * s, 1.45 * s
        b.cylinder((0.0, 0.0, 0.0), r * 0.95, 0.06 * s, DARK, METAL, segments=12)
        b.cylinder((0.0, 0.05 * s, 0.0), r, h - 0.1 * s, color, mat, segments=16)
        b.cylinder((0.0, h - 0.05 * s, 0.0), r, 0.05 * s, color, mat, 16, r * 0.8)
        for x in (-r * 0.45, r * 0.45):
            b.cylinder((x, h - 0.02 * s, 0.0), 0.018 * s, 0.25 * s, copper, METAL, segments=6)
        b.box((0.0, h * 0.35, r + 0.01), (0.16 * s, 0.2 * s, 0.03), DARK, PLASTIC)
        b.cylinder(
            (0.0, h * 0.35, r + 0.025), 0.025 * s, 0.02, color_rgb("red"), PLASTIC, 8, axis="z"
        )
        return ObjectModel(b.build())
    w, h, d = 0.42 * s, 0.7 * s, 0.3 * s
    y0 = 0.6 * s  # hung over a cupboard-high gap, pipes run down to the floor
    b.box((0.0, y0 + h / 2, 0.0), (w, h, d), color, mat)
    b.box((0.0, y0 + 0.1 * s, d / 2 + 0.005), (w * 0.6, 0.08 * s, 0.01), DARK, PLASTIC)
    b.box((-w * 0.15, y0 + 0.1 * s, d / 2 + 0.011), (0.06 * s, 0.03 * s, 0.004), BLACK, GLASS)
    for k in range(3):
        b.cylinder((-w * 0.3 + k * w * 0.3, 0.0, 0.0), 0.015 * s, y0, copper, METAL, segments=6)
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="oven",
        shapes={"single": "built-in oven", "double": "double oven"},
        colors=APPLIANCE_COLORS,
        materials=("metal",),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 0.4},
        build=build_oven,
    ),
    Category(
        name="range hood",
        shapes={"chimney": "chimney range hood", "flat": "slimline range hood"},
        colors=("silver", "white", "black", "gray"),
        materials=("metal",),
        placement=Placement.WALL_MOUNTED,
        rooms={"kitchen": 0.7},
        build=build_range_hood,
        wall_height=1.6,
    ),
    Category(
        name="clothes dryer",
        shapes={"front-loading": "tumble dryer", "compact": "compact dryer"},
        colors=APPLIANCE_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"storage room": 0.35, "bathroom": 0.15, "kitchen": 0.08},
        build=build_clothes_dryer,
    ),
    Category(
        name="air conditioner",
        shapes={"split": "split air conditioner", "slim": "slim air conditioner"},
        colors=("white", "cream", "silver", "gray"),
        materials=("plastic",),
        placement=Placement.WALL_MOUNTED,
        rooms={"bedroom": 0.3, "living room": 0.3, "study": 0.2, "gym": 0.3, "dining room": 0.1},
        build=build_air_conditioner,
        wall_height=2.0,
    ),
    Category(
        name="water cooler",
        shapes={"bottled": "bottled water cooler"},
        colors=("white", "silver", "gray", "black"),
        materials=("plastic", "metal"),
        placement=Placement.CORNER,
        rooms={"kitchen": 0.1, "gym": 0.3, "corridor": 0.05, "study": 0.05, "dining room": 0.05},
        build=build_water_cooler,
    ),
    Category(
        name="water heater",
        shapes={"tank": "water heater tank", "boiler": "wall boiler"},
        colors=("white", "silver", "cream", "gray"),
        materials=("metal",),
        placement=Placement.CORNER,
        rooms={"storage room": 0.5, "bathroom": 0.1, "kitchen": 0.05},
        build=build_water_heater,
    ),
]
