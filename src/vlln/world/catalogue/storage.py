"""Storage furniture: cabinets, wardrobes, bookshelves, drawers, shelves, shoe racks, counters."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import (
    FRONT_RECESS,
    GLASS,
    GLASS_RGB,
    METAL,
    PAINT_COLORS,
    PLAIN,
    WOOD_COLORS,
    add_carcass,
    add_framed_mirror,
    add_fronts,
    add_legs,
    add_top,
    worktop_finish,
)
from vlln.world.catalogue.parts import shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import MeshBuilder

BOOK_COLORS = ("red", "navy", "dark green", "beige", "brown", "black", "white", "orange", "teal")
SHOE_COLORS = ("black", "brown", "white", "red", "navy", "gray")


def build_cabinet(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Doors on short legs; the sideboard adds drawers, the display cabinet a glass case."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    long = style.shape == "sideboard"
    width = (1.5 if long else 0.8) * s + float(rng.uniform(0.0, 0.1))
    depth, height, leg_h = 0.45 * s, (0.8 if long else 0.9) * s, 0.1 * s
    b = MeshBuilder()
    add_legs(b, width - 0.04, depth - 2 * FRONT_RECESS, leg_h, 0.04, color, mat)
    z_front = add_carcass(b, width, depth, (leg_h, height - 0.025), color, mat)
    add_top(b, width + 0.02, depth, height, 0.025, color, mat)
    xs, fy0, fy1 = (-width / 2, width / 2), leg_h + 0.005, height - 0.03
    if long:
        split = fy1 - 0.18 * s
        add_fronts(b, xs, (split, fy1), z_front, (3, 1), color, mat, "drawer")
        add_fronts(b, xs, (fy0, split), z_front, (3, 1), color, mat, "door")
    else:
        add_fronts(b, xs, (fy0, fy1), z_front, (2, 1), color, mat, "door")
    if style.shape != "display":
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])
    case_d, case_h, t = 0.3 * s, 1.0 * s, 0.02
    zc, y1 = -depth / 2 + case_d / 2, height + case_h
    for sx in (-1.0, 1.0):
        b.box((sx * (width / 2 - t / 2), height + case_h / 2, zc), (t, case_h, case_d), color, mat)
    b.box((0.0, y1 - t / 2, zc), (width, t, case_d), color, mat)
    b.box((0.0, height + case_h / 2, -depth / 2 + 0.005), (width, case_h, 0.01), color, mat)
    for k in (1, 2):
        b.box((0.0, height + k * case_h / 3, zc), (width - 2 * t, t, case_d - 0.02), color, mat)
    for sx in (-1.0, 1.0):
        pane = ((width - 2 * t) / 2 - 0.006, case_h - t, 0.008)
        centre = (sx * (width - 2 * t) / 4, height + (case_h - t) / 2, zc + case_d / 2 - 0.004)
        b.box(centre, pane, GLASS_RGB, GLASS)
    strip = depth - case_d
    return ObjectModel(b.build(), [Surface(height, (0.0, depth / 2 - strip / 2), (width, strip))])


def build_wardrobe(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall carcass on a recessed plinth with full-height doors."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    doors = 3 if style.shape == "three-door" else 2
    width, depth = 0.5 * doors * s, 0.6 * s
    height, plinth = 2.0 * s + float(rng.uniform(-0.05, 0.05)), 0.08
    b = MeshBuilder()
    b.box(
        (0.0, plinth / 2, -0.05),
        (width - 0.04, plinth, depth - 0.1),
        shade(color, 0.6),
        mat,
        faces="+x-x+z-z",
    )
    z_front = add_carcass(b, width, depth, (plinth, height - 0.03), color, mat)
    add_top(b, width + 0.03, depth, height, 0.03, color, mat)
    add_fronts(
        b,
        (-width / 2, width / 2),
        (plinth, height - 0.035),
        z_front,
        (doors, 1),
        color,
        mat,
        "door",
    )
    return ObjectModel(b.build())


def build_bookshelf(style: Style, rng: np.random.Generator) -> ObjectModel:
    """An open case with a back panel; each board holds a row of books and free space."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    tall = style.shape == "tall"
    width, depth = (0.8 if tall else 1.0) * s, 0.3 * s
    height, gaps, t, base = (1.8 if tall else 0.85) * s, (5 if tall else 2), 0.02, 0.06
    inner = width - 2 * t
    b = MeshBuilder()
    for sx in (-1.0, 1.0):
        b.box((sx * (width / 2 - t / 2), height / 2, 0.0), (t, height, depth), color, mat)
    b.box((0.0, height / 2, -depth / 2 + 0.005), (inner, height, 0.01), shade(color, 0.8), mat)
    b.box((0.0, base / 2, 0.0), (inner, base, depth), color, mat, faces="+y+z")
    pitch = (height - base) / gaps
    surfaces = [Surface(height, (0.0, 0.0), (width, depth))] if not tall else []
    for k in range(gaps + 1):
        y = base + k * pitch
        if k > 0:
            b.box((0.0, y - t / 2, 0.0), (inner, t, depth - 0.01), color, mat)
        if k == gaps:
            break
        side = float(rng.choice([-1.0, 1.0]))
        x = -inner / 2 + 0.005
        for _ in range(int(rng.integers(4, 9))):
            bw, bd = float(rng.uniform(0.025, 0.05)), float(rng.uniform(0.15, 0.2)) * s
            bh = min(pitch - t - 0.03, float(rng.uniform(0.18, 0.28)) * s)
            book = color_rgb(str(rng.choice(BOOK_COLORS)))
            centre = (side * (x + bw / 2), y + bh / 2, depth / 2 - 0.02 - bd / 2)
            b.box(centre, (bw, bh, bd), book, PLAIN, faces="+x-x+y+z")
            x += bw
        free = inner / 2 - 0.01 - (x + 0.02)
        centre_x = side * (x + 0.02 + free / 2)
        surfaces.append(Surface(y, (centre_x, 0.005), (free, depth - 0.03)))
    return ObjectModel(b.build(), surfaces)


def build_dresser(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wide, low chest of two columns of drawers; optionally with a mirror on its top."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width = 1.2 * s + float(rng.uniform(0.0, 0.1))
    depth, height, leg_h = 0.5 * s, 0.8 * s, 0.1 * s
    b = MeshBuilder()
    add_legs(b, width - 0.04, depth - 2 * FRONT_RECESS, leg_h, 0.05, color, mat)
    z_front = add_carcass(b, width, depth, (leg_h, height - 0.025), color, mat)
    add_top(b, width + 0.02, depth, height, 0.025, color, mat)
    add_fronts(
        b,
        (-width / 2, width / 2),
        (leg_h + 0.005, height - 0.03),
        z_front,
        (2, 3),
        color,
        mat,
        "drawer",
    )
    if style.shape != "with mirror":
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])
    add_framed_mirror(b, 0.7 * width, 0.8 * s, height, -depth / 2, color, mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.015), (width, depth - 0.03))])


def build_chest_of_drawers(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A tall single column of drawers, the top row split in two, on a plinth."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    rows = 5 if style.shape == "five-drawer" else 4
    width, depth = 0.8 * s + float(rng.uniform(0.0, 0.06)), 0.45 * s
    height, plinth = (0.22 * rows + 0.12) * s, 0.08 * s
    b = MeshBuilder()
    z_front = add_carcass(b, width, depth, (0.0, height - 0.025), color, mat)
    add_top(b, width + 0.02, depth, height, 0.025, color, mat)
    xs, row_h = (-width / 2, width / 2), (height - 0.03 - plinth) / rows
    add_fronts(b, xs, (plinth, height - 0.03 - row_h), z_front, (1, rows - 1), color, mat)
    add_fronts(b, xs, (height - 0.03 - row_h, height - 0.03), z_front, (2, 1), color, mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_shelf(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wall board on two brackets, or a two-tier unit with side panels."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width = (0.6 + float(rng.uniform(0.0, 0.3))) * s
    depth, t = 0.22 * s, 0.025
    b = MeshBuilder()
    if style.shape == "two-tier":
        height = 0.35 * s
        for sx in (-1.0, 1.0):
            b.box((sx * (width / 2 - t / 2), height / 2, 0.0), (t, height, depth), color, mat)
        for y in (t, height):
            b.box((0.0, y - t / 2, 0.0), (width - 2 * t, t, depth), color, mat)
        return ObjectModel(
            b.build(), [Surface(y, (0.0, 0.0), (width - 2 * t, depth)) for y in (t, height)]
        )
    bracket, rise = color_rgb("dark gray"), 0.15 * s
    for sx in (-1.0, 1.0):
        x = sx * width / 3
        b.box((x, rise / 2, -depth / 2 + 0.005), (0.02, rise, 0.01), bracket, METAL)
        b.box((x, rise - 0.01, 0.0), (0.02, 0.02, depth - 0.02), bracket, METAL)
    b.box((0.0, rise + t / 2, 0.0), (width, t, depth), color, mat)
    return ObjectModel(b.build(), [Surface(rise + t, (0.0, 0.0), (width, depth))])


def build_shoe_rack(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Open slatted tiers with pairs of shoes, or a closed cabinet with flip-down fronts."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width, depth = 0.8 * s, 0.32 * s
    b = MeshBuilder()
    if style.shape == "cabinet":
        height = 0.95 * s
        z_front = add_carcass(b, width, depth, (0.0, height - 0.02), color, mat)
        add_top(b, width + 0.02, depth, height, 0.02, color, mat)
        add_fronts(b, (-width / 2, width / 2), (0.06, height - 0.025), z_front, (1, 2), color, mat)
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])
    height, t = 0.5 * s, 0.02
    for sx in (-1.0, 1.0):
        b.box((sx * (width / 2 - t / 2), height / 2, 0.0), (t, height, depth), color, mat)
    b.box((0.0, height - t / 2, 0.0), (width - 2 * t, t, depth), color, mat)
    for tier in (0.06 * s, 0.27 * s):
        for sz in (-1.0, 1.0):
            slat = (width - 2 * t, t, 0.35 * depth)
            b.box((0.0, tier - t / 2, sz * 0.3 * depth), slat, color, mat)
        x = -width / 2 + t + 0.02
        room = int((width - 2 * t - 0.02) // 0.23)
        for _ in range(int(rng.integers(1, room + 1))):
            shoe = color_rgb(str(rng.choice(SHOE_COLORS)))
            for _foot in range(2):
                b.box(
                    (x + 0.045, tier + 0.01, 0.0),
                    (0.09, 0.02, 0.26),
                    shoe,
                    PLAIN,
                    faces="+x-x+y+z-z",
                )
                b.box(
                    (x + 0.045, tier + 0.05, -0.05),
                    (0.08, 0.06, 0.15),
                    shoe,
                    PLAIN,
                    faces="+x-x+y+z-z",
                )
                x += 0.1
            x += 0.03
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width - 2 * t, depth))])


def build_kitchen_counter(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Base cabinets on a dark plinth under a worktop: drawers over doors, or all drawers."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    front_mat = material_index("wood" if style.material == "wood" else "plain")
    units = int(rng.integers(3, 5))
    width, depth, height, plinth = 0.6 * units * s, 0.62 * s, 0.9 * s, 0.1 * s
    top_rgb, top_mat = worktop_finish(style)
    b = MeshBuilder()
    b.box(
        (0.0, plinth / 2, -0.06),
        (width, plinth, depth - 0.12),
        color_rgb("black"),
        mat,
        faces="+x-x+z-z",
    )
    z_front = add_carcass(b, width, depth, (plinth, height - 0.04), color, front_mat)
    add_top(b, width, depth, height, 0.04, top_rgb, top_mat)
    xs, fy1 = (-width / 2, width / 2), height - 0.045
    if style.shape == "with drawers":
        add_fronts(b, xs, (plinth, fy1), z_front, (units, 3), color, front_mat)
    else:
        split = fy1 - 0.16 * s
        add_fronts(b, xs, (split, fy1), z_front, (units, 1), color, front_mat)
        add_fronts(b, xs, (plinth, split), z_front, (units, 1), color, front_mat, "door")
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


CATEGORIES: list[Category] = [
    Category(
        name="cabinet",
        shapes={"two-door": "cabinet", "sideboard": "sideboard", "display": "display cabinet"},
        colors=(*WOOD_COLORS, "cream"),
        materials=("wood", "plain", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={
            "living room": 0.5,
            "dining room": 0.6,
            "kitchen": 0.3,
            "study": 0.4,
            "bedroom": 0.3,
            "bathroom": 0.3,
            "corridor": 0.3,
            "storage room": 1.2,
            "gym": 0.2,
        },
        build=build_cabinet,
    ),
    Category(
        name="wardrobe",
        shapes={"two-door": "wardrobe", "three-door": "large wardrobe"},
        colors=WOOD_COLORS,
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.9, "corridor": 0.2, "storage room": 0.4},
        build=build_wardrobe,
    ),
    Category(
        name="bookshelf",
        shapes={"tall": "bookcase", "low": "low bookshelf"},
        colors=WOOD_COLORS,
        materials=("wood", "plain", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={"study": 1.0, "living room": 0.5, "bedroom": 0.3},
        build=build_bookshelf,
    ),
    Category(
        name="dresser",
        shapes={"low": "dresser", "with mirror": "dresser with mirror"},
        colors=WOOD_COLORS,
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.5, "corridor": 0.1},
        build=build_dresser,
    ),
    Category(
        name="drawer",
        shapes={"four-drawer": "chest of drawers", "five-drawer": "tall chest of drawers"},
        colors=WOOD_COLORS,
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.5, "study": 0.1, "corridor": 0.1, "storage room": 0.2},
        build=build_chest_of_drawers,
    ),
    Category(
        name="shelf",
        shapes={"bracketed": "wall shelf", "two-tier": "two-tier wall shelf"},
        colors=(*WOOD_COLORS, "silver"),
        materials=("wood", "glass", "metal"),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "living room": 0.5,
            "kitchen": 0.6,
            "bedroom": 0.4,
            "study": 0.6,
            "bathroom": 0.5,
            "toilet": 0.2,
            "storage room": 0.6,
            "gym": 0.3,
        },
        build=build_shelf,
        wall_height=1.4,
    ),
    Category(
        name="shoe rack",
        shapes={"open": "shoe rack", "cabinet": "shoe cabinet"},
        colors=WOOD_COLORS,
        materials=("wood", "metal", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"corridor": 0.8, "storage room": 0.2, "bedroom": 0.1},
        build=build_shoe_rack,
    ),
    Category(
        name="counter",
        shapes={"with doors": "kitchen counter", "with drawers": "drawer counter"},
        colors=PAINT_COLORS,
        materials=("marble", "wood", "plastic"),
        placement=Placement.AGAINST_WALL,
        rooms={"kitchen": 1.5},
        build=build_kitchen_counter,
    ),
]
