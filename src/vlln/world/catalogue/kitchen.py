"""Large kitchen and laundry appliances; the countertop ones come from :mod:`countertop`."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue import countertop
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.parts import ring, shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

APPLIANCE_COLORS = ("white", "silver", "black", "gray", "cream")
METAL = material_index("metal")
GLASS = material_index("glass")
PLASTIC = material_index("plastic")
BLACK = color_rgb("black")
DARK = color_rgb("dark gray")


def _handle_color(color: Rgb) -> Rgb:
    """Chrome handles on coloured appliances, dark ones on silver appliances."""
    return DARK if color == color_rgb("silver") else color_rgb("silver")


def _bar_handle(
    b: MeshBuilder, x: float, y: float, z_front: float, length: float, vertical: bool, c: Rgb
) -> None:
    """A bar handle standing off the door front at ``z_front`` on two short posts."""
    off, bar = 0.03, 0.018
    size = (bar, length, bar) if vertical else (length, bar, bar)
    b.box((x, y, z_front + off), size, c, METAL)
    for k in (-1, 1):
        dx, dy = (0.0, k * length * 0.4) if vertical else (k * length * 0.4, 0.0)
        b.box((x + dx, y + dy, z_front + off / 2), (0.012, 0.012, off), c, METAL)


def build_refrigerator(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall box with doors and bar handles: stacked doors, side-by-side doors or a mini."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    handle = _handle_color(color)
    w, d, h = {"two-door": (0.6, 0.65, 1.8), "side-by-side": (0.9, 0.7, 1.78)}.get(
        style.shape, (0.5, 0.5, 0.85)
    )
    w, d, h = w * s, d * s, (h + float(rng.uniform(-0.05, 0.08))) * s
    door_t, gap = 0.04 * s, 0.008
    front = d / 2 - door_t
    b = MeshBuilder()
    b.box((0.0, h / 2, -door_t / 2), (w, h, d - door_t), color, mat)
    if style.shape == "side-by-side":
        split = -0.06 * w
        for x0, x1, hx in ((-w / 2, split, split - 0.05), (split, w / 2, split + 0.05)):
            b.box(
                ((x0 + x1) / 2, h / 2, front + door_t / 2),
                (x1 - x0 - gap, h - 0.02, door_t),
                color,
                mat,
            )
            _bar_handle(b, hx, h * 0.6, front + door_t, h * 0.5, True, handle)
        b.box(
            (-w * 0.28, h * 0.62, front + door_t + 0.002),
            (w * 0.22, h * 0.16, 0.004),
            DARK,
            PLASTIC,
        )
    else:
        split = h * (0.37 if style.shape == "two-door" else 0.0)
        doors = [(0.01, split), (split, h - 0.01)] if split > 0 else [(0.01, h - 0.01)]
        for y0, y1 in doors:
            b.box(
                (0.0, (y0 + y1) / 2, front + door_t / 2),
                (w - 0.01, y1 - y0 - gap, door_t),
                color,
                mat,
            )
            top = y1 - 0.08 * s if y0 > 0.05 or split == 0 else y1 - 0.05 * s
            length = min(0.45 * s, (y1 - y0) * 0.5)
            _bar_handle(b, w / 2 - 0.06 * s, top - length / 2, front + door_t, length, True, handle)
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_stove(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An oven with a glass door, a row of knobs and a hob of gas burners or cooking rings."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, h = 0.6 * s, 0.6 * s, 0.88 * s
    top_t = 0.02 * s
    b = MeshBuilder()
    b.box((0.0, (h - top_t) / 2, 0.0), (w, h - top_t, d), color, mat)
    zf = d / 2
    b.box((0.0, 0.05 * s, zf + 0.003), (w * 0.96, 0.08 * s, 0.006), DARK, PLASTIC)
    b.box((0.0, 0.4 * s, zf + 0.01), (w * 0.92, 0.5 * s, 0.02), shade(color, 0.92), mat)
    b.box((0.0, 0.38 * s, zf + 0.021), (w * 0.6, 0.28 * s, 0.004), BLACK, GLASS)
    _bar_handle(b, 0.0, 0.6 * s, zf + 0.02, w * 0.7, False, _handle_color(color))
    n_knobs = 4 + int(rng.integers(0, 2))
    for k in range(n_knobs):
        x = (k - (n_knobs - 1) / 2) * w * 0.16
        b.cylinder((x, 0.76 * s, zf), 0.02 * s, 0.025 * s, DARK, PLASTIC, segments=6, axis="z")
    hob = BLACK if style.shape == "electric" else shade(color, 0.85)
    b.box(
        (0.0, h - top_t / 2, 0.0), (w, top_t, d), hob, GLASS if style.shape == "electric" else mat
    )
    burners = [
        (x * w * 0.24, z * d * 0.22, 0.075 * s if x * z > 0 else 0.06 * s)
        for x in (-1, 1)
        for z in (-1, 1)
    ]
    for x, z, r in burners:
        if style.shape == "electric":
            b.cylinder((x, h, z), r, 0.001, DARK, GLASS, segments=10)
        else:
            b.cylinder((x, h, z), r * 0.6, 0.02 * s, DARK, METAL, segments=6)
    if style.shape != "electric":  # pan supports: two bars each way over the burners
        for k in (-1, 1):
            b.box((0.0, h + 0.025 * s, k * d * 0.22), (w * 0.8, 0.01, 0.01), BLACK, METAL)
            b.box((k * w * 0.24, h + 0.025 * s, 0.0), (0.01, 0.01, d * 0.75), BLACK, METAL)
    hob_y = h + (0.001 if style.shape == "electric" else 0.03 * s)  # pans sit on the supports
    return ObjectModel(b.build(), [Surface(hob_y, (0.0, 0.0), (w, d))])


def build_dishwasher(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A counter-high box: a full-height door, a control strip on top and a bar handle."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w = (0.45 if style.shape == "compact" else 0.6) * s
    d, h = 0.6 * s, 0.85 * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    b.box((0.0, 0.05 * s, zf + 0.003), (w * 0.96, 0.09 * s, 0.006), DARK, PLASTIC)
    b.box((0.0, 0.44 * s, zf + 0.01), (w - 0.01, 0.66 * s, 0.02), shade(color, 0.95), mat)
    b.box((0.0, 0.81 * s, zf + 0.004), (w - 0.01, 0.06 * s, 0.008), DARK, PLASTIC)
    n_buttons = int(rng.integers(3, 6))
    for k in range(n_buttons):
        b.box(
            (w * (0.1 + 0.07 * k), 0.81 * s, zf + 0.01),
            (0.02, 0.012, 0.006),
            color_rgb("light gray"),
            PLASTIC,
            faces="+z+y",
        )
    _bar_handle(b, 0.0, 0.72 * s, zf + 0.02, w * 0.7, False, _handle_color(color))
    return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])


def build_washing_machine(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A cube with a round porthole door (front-loading) or a lid and a back panel (top)."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    w, d, h = 0.6 * s, 0.6 * s, 0.85 * s
    b = MeshBuilder()
    b.box((0.0, h / 2, 0.0), (w, h, d), color, mat)
    zf = d / 2
    knob_x = w * float(rng.choice([-0.3, 0.3]))
    if style.shape == "front-loading":
        door_y, r = 0.42 * s, 0.18 * s
        ring(
            b,
            (0.0, door_y, zf + 0.02),
            r,
            0.045 * s,
            0.04,
            color_rgb("light gray"),
            PLASTIC,
            segments=14,
        )
        b.cylinder(
            (0.0, door_y, zf), r - 0.04 * s, 0.03, color_rgb("navy"), GLASS, segments=14, axis="z"
        )
        b.box((0.0, h - 0.06 * s, zf + 0.004), (w - 0.02, 0.09 * s, 0.008), shade(color, 0.9), mat)
        b.box(
            (-knob_x, h - 0.06 * s, zf + 0.01), (0.14 * s, 0.06 * s, 0.01), shade(color, 0.8), mat
        )
        b.cylinder((knob_x, h - 0.06 * s, zf), 0.03 * s, 0.03, DARK, PLASTIC, segments=10, axis="z")
        return ObjectModel(b.build(), [Surface(h, (0.0, 0.0), (w, d))])
    b.box((0.0, h + 0.005, 0.05 * s), (w * 0.8, 0.01, d * 0.7), shade(color, 0.9), mat)
    panel_d, panel_h = 0.1 * s, 0.14 * s
    b.box((0.0, h + panel_h / 2, -d / 2 + panel_d / 2), (w, panel_h, panel_d), color, mat)
    b.cylinder(
        (knob_x, h + panel_h / 2, -d / 2 + panel_d),
        0.03 * s,
        0.03,
        DARK,
        PLASTIC,
        segments=10,
        axis="z",
    )
    b.box(
        (-knob_x, h + panel_h / 2, -d / 2 + panel_d + 0.002),
        (0.12 * s, 0.04 * s, 0.004),
        BLACK,
        GLASS,
    )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="refrigerator",
        shapes={
            "two-door": "fridge-freezer",
            "side-by-side": "side-by-side refrigerator",
            "mini": "mini fridge",
        },
        colors=(*APPLIANCE_COLORS, "red"),
        materials=("metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 1.0, "storage room": 0.1},
        build=build_refrigerator,
    ),
    Category(
        name="stove",
        shapes={"gas": "gas stove", "electric": "electric stove"},
        colors=APPLIANCE_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 0.9},
        build=build_stove,
    ),
    Category(
        name="dishwasher",
        shapes={"standard": "dishwasher", "compact": "slimline dishwasher"},
        colors=APPLIANCE_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 0.5},
        build=build_dishwasher,
    ),
    Category(
        name="washing machine",
        shapes={
            "front-loading": "front-loading washing machine",
            "top-loading": "top-loading washing machine",
        },
        colors=("white", "silver", "gray"),
        materials=("metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"bathroom": 0.4, "kitchen": 0.25, "storage room": 0.5},
        build=build_washing_machine,
    ),
    *countertop.CATEGORIES,
]
