"""Bathroom fixtures and accessories: toilets, sinks, tubs, showers, towels, mirrors, mats."""

from __future__ import annotations

import math

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import (
    FRONT_RECESS,
    GLASS,
    GLASS_RGB,
    METAL,
    MIRROR_RGB,
    PLAIN,
    add_carcass,
    add_framed_mirror,
    add_fronts,
    add_legs,
    add_top,
)
from vlln.world.catalogue.parts import ring, shade
from vlln.world.materials import color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder

CERAMIC = material_index("ceramic")
FABRIC = material_index("fabric")
CHROME = color_rgb("silver")
SANITARY_COLORS = ("white", "cream", "light gray", "black")
TEXTILE_COLORS = ("white", "beige", "light blue", "gray", "navy", "pink", "green", "cream")
FITTING_COLORS = ("silver", "black", "gold", "white")


def _centred(mesh: Mesh) -> Mesh:
    """The mesh moved so that its footprint is centred on the origin (for wall fittings)."""
    lo, hi = mesh.bounds()
    return mesh.transformed(0.0, (-float(lo[0] + hi[0]) / 2, 0.0, -float(lo[2] + hi[2]) / 2))


def _tap(b: MeshBuilder, x: float, y: float, z: float, reach: float, s: float) -> None:
    """A chrome pillar tap standing at (x, y, z) with its spout pointing to +z."""
    height = 0.16 * s
    b.cylinder((x, y, z), 0.016, height, CHROME, METAL, 8)
    b.cylinder((x, y + height - 0.03, z), 0.012, reach, CHROME, METAL, 8, axis="z")
    b.box((x, y + height + 0.01, z), (0.08, 0.015, 0.02), CHROME, METAL)


def build_toilet(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A bowl on a pedestal with a seat, its lid up against a cistern at the back."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    seat = color if rng.uniform() < 0.7 else color_rgb("white")
    bowl_z, rim_y = 0.12 * s, 0.4 * s
    tank = (0.4 * s, 0.38 * s, 0.17 * s)
    tank_z = -0.34 * s + tank[2] / 2
    b = MeshBuilder()
    b.box((0.0, rim_y + 0.02 + tank[1] / 2, tank_z), tank, color, mat)
    b.cylinder((0.0, rim_y + 0.02 + tank[1], tank_z), 0.02, 0.01, CHROME, METAL, 8)
    back = (0.28 * s, rim_y - 0.05, bowl_z - tank_z)
    b.box((0.0, (rim_y + 0.05) / 2, (bowl_z + tank_z) / 2), back, color, mat)
    radius = 0.19 * s
    if style.shape == "square":
        b.box((0.0, 0.15 * s, bowl_z), (0.24 * s, 0.3 * s, 0.3 * s), color, mat)
        b.box((0.0, rim_y - 0.05 * s, bowl_z), (2 * radius, 0.1 * s, 2 * radius), color, mat)
        inner = (2 * radius - 0.1, 0.004, 2 * radius - 0.1)
        b.box((0.0, rim_y + 0.002, bowl_z), inner, shade(color, 0.7), mat, faces="+y")
    else:
        b.cylinder((0.0, 0.0, bowl_z), 0.14 * s, 0.26 * s, color, mat, 12, radius_top=0.11 * s)
        b.cylinder(
            (0.0, 0.26 * s, bowl_z), 0.12 * s, rim_y - 0.26 * s, color, mat, 12, radius_top=radius
        )
        b.cylinder((0.0, rim_y, bowl_z), radius - 0.05, 0.004, shade(color, 0.7), mat, 12)
    ring(b, (0.0, rim_y + 0.012, bowl_z), radius, 0.055, 0.024, seat, PLAIN, axis="y")
    lid_z = tank_z + tank[2] / 2
    b.cylinder((0.0, rim_y + 0.03 + radius, lid_z), radius, 0.02, seat, PLAIN, 12, axis="z")
    return ObjectModel(b.build())


def build_sink(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A washbasin with a tap: set into a vanity cabinet's top, or on a pedestal."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "pedestal":
        top, radius = 0.85 * s, 0.26 * s
        b.cylinder((0.0, 0.0, -0.05), 0.1 * s, top - 0.16 * s, color, mat, 10, radius_top=0.07)
        b.cylinder(
            (0.0, top - 0.17 * s, 0.0), 0.15 * s, 0.17 * s, color, mat, 12, radius_top=radius
        )
        b.cylinder((0.0, top, 0.03), radius - 0.07, 0.004, shade(color, 0.7), mat, 12)
        _tap(b, 0.0, top, -radius + 0.05, 0.1 * s, s)
        return ObjectModel(b.build())
    width = (0.8 + float(rng.uniform(0.0, 0.2))) * s
    depth, top, leg_h = 0.5 * s, 0.85 * s, 0.12 * s
    add_legs(b, width - 0.04, depth - 2 * FRONT_RECESS, leg_h, 0.04, CHROME, METAL)
    z_front = add_carcass(b, width, depth, (leg_h, top - 0.03), color, mat)
    add_fronts(
        b,
        (-width / 2, width / 2),
        (leg_h + 0.005, top - 0.035),
        z_front,
        (2, 1),
        color,
        mat,
        "door",
    )
    add_top(b, width + 0.02, depth, top, 0.03, color, mat)
    white, basin_r = color_rgb("white"), 0.18 * s
    b.cylinder((0.0, top, 0.04 * s), basin_r, 0.008, white, CERAMIC, 12)
    b.cylinder((0.0, top + 0.008, 0.04 * s), basin_r - 0.03, 0.002, shade(white, 0.7), CERAMIC, 12)
    _tap(b, 0.0, top, -depth / 2 + 0.05, 0.1 * s, s)
    side = width / 2 - basin_r - 0.02
    surfaces = [Surface(top, (sx * (width / 2 - side / 2), 0.0), (side, depth)) for sx in (-1, 1)]
    return ObjectModel(b.build(), surfaces)


def build_bathtub(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A hollow tub with a tap: a boxed-in rectangle, or a free-standing oval on feet."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    inside = shade(color, 0.92)
    length = (1.6 + float(rng.uniform(0.0, 0.2))) * s
    width, height, wall = 0.75 * s, 0.56 * s, 0.07 * s
    b = MeshBuilder()
    if style.shape == "freestanding":
        foot, r = 0.07 * s, width / 2
        straight = length - width
        for sx in (-1.0, 1.0):
            for sz in (-1.0, 1.0):
                leg = (sx * straight / 2, 0.0, sz * 0.6 * r)
                b.cylinder(leg, 0.02, foot, CHROME, METAL, 6, radius_top=0.035, caps=False)
            arc = (-math.pi / 2, math.pi / 2) if sx > 0 else (math.pi / 2, 3 * math.pi / 2)
            end = (sx * straight / 2, (foot + height) / 2, 0.0)
            ring(b, end, r, wall, height - foot, color, mat, axis="y", segments=8, arc=arc)
            b.cylinder((sx * straight / 2, foot, 0.0), r - wall, 0.1 * s, inside, mat, 8)
        for sz in (-1.0, 1.0):
            side = (straight, height - foot, wall)
            b.box((0.0, (foot + height) / 2, sz * (r - wall / 2)), side, color, mat, faces="+y+z-z")
        b.box((0.0, foot + 0.05 * s, 0.0), (straight, 0.1 * s, width - 2 * wall), inside, mat)
        _tap(b, -straight / 2 - r + wall / 2, height, 0.0, 0.12 * s, s)
        return ObjectModel(b.build())
    for sz in (-1.0, 1.0):
        b.box((0.0, height / 2, sz * (width / 2 - wall / 2)), (length, height, wall), color, mat)
    for sx in (-1.0, 1.0):
        end = (wall, height, width - 2 * wall)
        b.box((sx * (length / 2 - wall / 2), height / 2, 0.0), end, color, mat)
    b.box(
        (0.0, 0.06 * s, 0.0),
        (length - 2 * wall, 0.12 * s, width - 2 * wall),
        inside,
        mat,
        faces="+y",
    )
    _tap(b, -length / 2 + wall / 2, height, 0.0, 0.12 * s, s)
    return ObjectModel(b.build())


def build_shower(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A low tray with glass panels on its open sides and a head on a riser at the back."""
    s = style.scale
    color = color_rgb(style.color)
    glass_mat = material_index(style.material)
    corner = style.shape == "corner"
    width, depth = (0.9 * s, 0.9 * s) if corner else (1.2 * s, 0.8 * s)
    height = 1.95 + float(rng.uniform(0.0, 0.15))  # doors are the same height everywhere
    tray_h, pane, frame = 0.05, 0.008, 0.02
    white = color_rgb("white")
    b = MeshBuilder()
    b.box((0.0, tray_h / 2, 0.0), (width, tray_h, depth), white, CERAMIC)
    b.cylinder((0.0, tray_h, 0.0), 0.04, 0.003, color_rgb("dark gray"), METAL, 8)
    panel_h, panel_y = height - tray_h, (height + tray_h) / 2
    front_w = width if corner else 0.55 * width
    front_x = -width / 2 + front_w / 2
    b.box((front_x, panel_y, depth / 2 - pane / 2), (front_w, panel_h, pane), GLASS_RGB, glass_mat)
    posts = [(-width / 2 + frame / 2, depth / 2 - frame / 2)]
    posts.append((front_x + front_w / 2 - frame / 2, depth / 2 - frame / 2))
    if corner:
        side = (pane, panel_h, depth - frame)
        b.box((width / 2 - pane / 2, panel_y, -frame / 2), side, GLASS_RGB, glass_mat)
        posts.append((width / 2 - frame / 2, -depth / 2 + frame / 2))
    for x, z in posts:
        b.box((x, panel_y, z), (frame, panel_h, frame), color, METAL, faces="+x-x+z-z")
    riser_z = -depth / 2 + 0.03
    b.cylinder((0.0, 0.9 * s, riser_z), 0.012, height - 0.1 - 0.9 * s, CHROME, METAL, 8)
    b.cylinder((0.0, height - 0.12, riser_z), 0.01, 0.22 * s, CHROME, METAL, 8, axis="z")
    b.cylinder((0.0, height - 0.15, riser_z + 0.22 * s), 0.1 * s, 0.025, CHROME, METAL, 10)
    b.box((0.0, 1.1 * s, riser_z), (0.16, 0.08, 0.05), CHROME, METAL)
    return ObjectModel(b.build())


def build_towel(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A towel folded over a chrome rail that stands off the wall on two brackets."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    bath = style.shape == "bath"
    width = (0.55 if bath else 0.32) * s
    hang = (0.7 if bath else 0.45) * s + float(rng.uniform(0.0, 0.05))
    rail_y, rail_z, fold = hang - 0.03, 0.06, 0.028
    b = MeshBuilder()
    b.cylinder((-width / 2 - 0.06, rail_y, rail_z), 0.01, width + 0.12, CHROME, METAL, 8, axis="x")
    for sx in (-1.0, 1.0):
        b.cylinder(
            (sx * (width / 2 + 0.045), rail_y, 0.0), 0.012, rail_z, CHROME, METAL, 8, axis="z"
        )
    b.cylinder((-width / 2, rail_y, rail_z), fold, width, color, mat, 10, axis="x")
    b.box((0.0, rail_y / 2, rail_z + fold - 0.01), (width, rail_y, 0.02), color, mat)
    back_h = 0.75 * rail_y
    b.box((0.0, rail_y - back_h / 2, rail_z - fold + 0.01), (width, back_h, 0.02), color, mat)
    return ObjectModel(_centred(b.build()))


def build_mirror(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A wall mirror in a frame, rectangular or round."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "round":
        radius = (0.3 + float(rng.uniform(0.0, 0.08))) * s
        b.cylinder((0.0, radius, -0.015), radius, 0.025, color, mat, 12, axis="z")
        b.cylinder((0.0, radius, 0.01), radius - 0.04, 0.005, MIRROR_RGB, GLASS, 12, axis="z")
        return ObjectModel(b.build())
    width = (0.55 + float(rng.uniform(0.0, 0.15))) * s
    add_framed_mirror(b, width, 0.8 * s, 0.0, -0.015, color, mat)
    return ObjectModel(b.build())


def build_toilet_paper(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A roll on a wall holder's bar, its loose end hanging; the covered holder has a flap."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    radius, roll_w, sheet = 0.055 * s, 0.1 * s, 0.09 * s + float(rng.uniform(0.0, 0.04))
    axle_y, axle_z = sheet + radius, radius + 0.02
    white = color_rgb("white")
    b = MeshBuilder()
    b.box((-roll_w / 2 - 0.02, axle_y, 0.005), (0.02, 0.07, 0.01), color, mat)
    b.cylinder((-roll_w / 2 - 0.02, axle_y, 0.0), 0.008, axle_z, color, mat, 8, axis="z")
    b.cylinder((-roll_w / 2 - 0.02, axle_y, axle_z), 0.008, roll_w + 0.03, color, mat, 8, axis="x")
    b.cylinder((-roll_w / 2, axle_y, axle_z), radius, roll_w, white, PLAIN, 12, axis="x")
    b.box((0.0, axle_y / 2, axle_z + radius), (roll_w, axle_y, 0.003), white, PLAIN)
    if style.shape == "covered":
        flap = (roll_w + 0.05, 0.006, 2 * radius + 0.03)
        b.box((-0.01, axle_y + radius + 0.01, axle_z), flap, color, mat)
    return ObjectModel(_centred(b.build()))


def build_bath_mat(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A thin fabric mat, rectangular or round."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    b = MeshBuilder()
    if style.shape == "round":
        b.cylinder((0.0, 0.0, 0.0), (0.3 + float(rng.uniform(0.0, 0.05))) * s, 0.015, color, mat)
        return ObjectModel(b.build())
    size = ((0.75 + float(rng.uniform(0.0, 0.1))) * s, 0.015, 0.5 * s)
    b.box((0.0, 0.0075, 0.0), size, color, mat, faces="+x-x+y+z-z")
    return ObjectModel(b.build())


def build_laundry_basket(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A round open basket heaped with clothes, or a lidded box hamper with hand holes."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    height = (0.52 + float(rng.uniform(0.0, 0.08))) * s
    b = MeshBuilder()
    if style.shape == "hamper":
        width, depth = 0.45 * s, 0.33 * s
        b.box((0.0, (height - 0.03) / 2, 0.0), (width, height - 0.03, depth), color, mat)
        b.box((0.0, height - 0.015, 0.0), (width + 0.02, 0.03, depth + 0.02), color, mat)
        for sx in (-1.0, 1.0):
            hole = (0.002, 0.03, 0.1)
            b.box((sx * (width / 2 + 0.001), height - 0.1, 0.0), hole, shade(color, 0.3), mat)
        return ObjectModel(b.build())
    radius = 0.23 * s
    clothes = color_rgb(str(rng.choice(TEXTILE_COLORS)))
    b.cylinder((0.0, 0.0, 0.0), 0.85 * radius, height - 0.03, color, mat, 12, radius_top=radius)
    ring(
        b, (0.0, height - 0.015, 0.0), radius + 0.01, 0.02, 0.03, shade(color, 0.85), mat, axis="y"
    )
    mound = (0.0, height - 0.03, 0.0)
    b.sphere(mound, radius - 0.01, clothes, FABRIC, 10, scale=(1.0, 0.45, 1.0))
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="toilet",
        shapes={"round": "toilet", "square": "square toilet"},
        colors=SANITARY_COLORS,
        materials=("ceramic",),
        placement=Placement.AGAINST_WALL,
        rooms={"bathroom": 1.0, "toilet": 1.0},
        build=build_toilet,
    ),
    Category(
        name="sink",
        shapes={"vanity": "vanity sink", "pedestal": "pedestal sink"},
        colors=(*SANITARY_COLORS, "brown", "navy", "beige"),
        materials=("ceramic", "wood", "marble"),
        placement=Placement.AGAINST_WALL,
        rooms={"bathroom": 1.0, "toilet": 0.8},
        build=build_sink,
    ),
    Category(
        name="bathtub",
        shapes={"built-in": "bathtub", "freestanding": "freestanding bathtub"},
        colors=SANITARY_COLORS,
        materials=("ceramic", "marble"),
        placement=Placement.AGAINST_WALL,
        rooms={"bathroom": 0.6},
        build=build_bathtub,
    ),
    Category(
        name="shower",
        shapes={"corner": "corner shower", "walk-in": "walk-in shower"},
        colors=FITTING_COLORS,
        materials=("glass",),
        placement=Placement.CORNER,
        rooms={"bathroom": 0.5},
        build=build_shower,
    ),
    Category(
        name="towel",
        shapes={"hand": "hand towel", "bath": "bath towel"},
        colors=TEXTILE_COLORS,
        materials=("fabric",),
        placement=Placement.WALL_MOUNTED,
        rooms={"bathroom": 2.0, "toilet": 0.8, "kitchen": 0.4, "gym": 0.6},
        build=build_towel,
        wall_height=1.1,
    ),
    Category(
        name="mirror",
        shapes={"rectangular": "wall mirror", "round": "round mirror"},
        colors=("gold", "silver", "black", "white", "brown"),
        materials=("wood", "metal", "plastic"),
        placement=Placement.WALL_MOUNTED,
        rooms={
            "bathroom": 1.0,
            "toilet": 0.6,
            "bedroom": 0.4,
            "corridor": 0.4,
            "living room": 0.2,
            "gym": 0.6,
        },
        build=build_mirror,
        wall_height=1.5,
    ),
    Category(
        name="toilet paper",
        shapes={"bar": "toilet roll", "covered": "toilet roll holder"},
        colors=FITTING_COLORS,
        materials=("metal", "plastic"),
        placement=Placement.WALL_MOUNTED,
        rooms={"bathroom": 0.9, "toilet": 1.0},
        build=build_toilet_paper,
        wall_height=0.7,
    ),
    Category(
        name="bath mat",
        shapes={"rectangular": "bath mat", "round": "round bath mat"},
        colors=TEXTILE_COLORS,
        materials=("fabric", "carpet"),
        placement=Placement.FLOOR,
        rooms={"bathroom": 0.8},
        build=build_bath_mat,
    ),
    Category(
        name="hamper",
        shapes={"round": "laundry basket", "hamper": "laundry hamper"},
        colors=("white", "beige", "gray", "light blue", "brown"),
        materials=("plastic", "fabric", "wood"),
        placement=Placement.CORNER,
        rooms={"bathroom": 0.4, "bedroom": 0.2, "storage room": 0.3},
        build=build_laundry_basket,
    ),
]
