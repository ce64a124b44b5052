"""Things to sit on: chairs, armchairs, sofas, stools, benches, ottomans and beanbags."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import METAL, WOOD_COLORS, add_legs
from vlln.world.catalogue.parts import shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import Mesh, MeshBuilder

WOOD = material_index("wood")
FABRIC = material_index("fabric")
PLASTIC = material_index("plastic")
UPHOLSTERY_COLORS = ("gray", "dark gray", "beige", "blue", "navy", "green", "brown", "red", "cream")


def build_chair(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Four legs, a seat and a back; the office variant has a pedestal and a padded back."""
    s = style.scale
    color = color_rgb(style.color)
    mat = material_index(style.material)
    leg_color = color_rgb("black") if style.shape == "office" else color
    b = MeshBuilder()
    width, depth, seat_h = 0.45 * s, 0.45 * s, 0.46 * s
    back_h = 0.45 * s + float(rng.uniform(0.0, 0.1))
    seat_t = 0.05
    if style.shape == "office":
        b.cylinder((0.0, 0.0, 0.0), 0.03, seat_h - seat_t, leg_color, METAL)
        for k in range(5):
            angle = 2.0 * np.pi * k / 5
            foot = (0.14 * np.cos(angle), 0.025, 0.14 * np.sin(angle))
            b.box(foot, (0.3, 0.04, 0.04), leg_color, PLASTIC, yaw=-angle)
    else:
        add_legs(b, width, depth, seat_h - seat_t, 0.04 * s, leg_color, mat)
    b.box((0.0, seat_h - seat_t / 2, 0.0), (width, seat_t, depth), color, mat)
    back_t = 0.06 if style.shape == "office" else 0.035
    b.box(
        (0.0, seat_h + back_h / 2, -depth / 2 + back_t / 2),
        (width, back_h, back_t),
        color,
        mat,
    )
    return ObjectModel(b.build(), [Surface(seat_h, (0.0, 0.0), (width, depth))])


def _sofa_body(
    b: MeshBuilder, width: float, seats: int, style: Style, back_top: float, arm_w: float
) -> Surface:
    """Legs, base, back, two arms and ``seats`` seat and back cushions; returns the seat."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    cushion = shade(color, 1.12)
    depth, back_t = 0.88 * s, 0.16 * s
    leg_h, base_top, seat_top, arm_top = 0.08 * s, 0.36 * s, 0.45 * s, 0.63 * s
    add_legs(b, width - 0.06, depth - 0.06, leg_h, 0.05, color_rgb("dark brown"), WOOD)
    b.box((0.0, (leg_h + base_top) / 2, 0.0), (width, base_top - leg_h, depth), color, mat)
    back_y = (base_top + back_top) / 2
    b.box((0.0, back_y, -depth / 2 + back_t / 2), (width, back_top - base_top, back_t), color, mat)
    for sx in (-1.0, 1.0):
        arm = (arm_w, arm_top - leg_h, depth)
        b.box((sx * (width / 2 - arm_w / 2), (leg_h + arm_top) / 2, 0.0), arm, color, mat)
    inner = width - 2 * arm_w
    pitch, lean_t = inner / seats, 0.13 * s
    seat_z0 = -depth / 2 + back_t + lean_t
    pad_h = (back_top - seat_top) * 0.8
    for k in range(seats):
        x = -inner / 2 + (k + 0.5) * pitch
        seat = (pitch - 0.012, seat_top - base_top, depth / 2 - seat_z0)
        b.box((x, (base_top + seat_top) / 2, (seat_z0 + depth / 2) / 2), seat, cushion, mat)
        pad = (pitch - 0.012, pad_h, lean_t)
        b.box((x, seat_top + pad_h / 2, seat_z0 - lean_t / 2), pad, cushion, mat)
    return Surface(seat_top, (0.0, (seat_z0 + depth / 2) / 2), (inner, depth / 2 - seat_z0))


def build_armchair(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A one-seat sofa; the wingback has a tall back with side wings."""
    s = style.scale
    width = (0.82 + float(rng.uniform(0.0, 0.08))) * s
    b = MeshBuilder()
    if style.shape != "wingback":
        seat = _sofa_body(b, width, 1, style, 0.82 * s, 0.16 * s)
        return ObjectModel(b.build(), [seat])
    color, mat = color_rgb(style.color), material_index(style.material)
    back_top, arm_w = 1.08 * s, 0.11 * s
    seat = _sofa_body(b, width, 1, style, back_top, arm_w)
    wing_h, wing_d = 0.4 * s, 0.22 * s
    for sx in (-1.0, 1.0):
        wing = (arm_w, wing_h, wing_d)
        centre = (sx * (width / 2 - arm_w / 2), back_top - 0.03 - wing_h / 2, -0.44 * s + wing_d)
        b.box(centre, wing, color, mat)
    return ObjectModel(b.build(), [seat])


def build_sofa(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Two or three seats between arms; the L-shaped one adds a chaise on its right."""
    s = style.scale
    seats = 2 if style.shape == "two-seat" else 3
    width = (0.6 * seats + 0.34 + float(rng.uniform(0.0, 0.15))) * s
    arm_w = 0.17 * s
    b = MeshBuilder()
    seat = _sofa_body(b, width, seats, style, 0.85 * s, arm_w)
    if style.shape != "L-shaped":
        return ObjectModel(b.build(), [seat])
    color, mat = color_rgb(style.color), material_index(style.material)
    depth, extra = 0.88 * s, 0.72 * s
    shift = -extra / 2
    chaise = MeshBuilder()
    cw = (width - 2 * arm_w) / seats
    z0, z1 = depth / 2 + shift, depth / 2 + extra / 2
    zc, x_in = (z0 + z1) / 2, width / 2 - arm_w - cw
    base_w = cw + arm_w
    leg_h, base_top, seat_top, arm_top = 0.08 * s, 0.36 * s, 0.45 * s, 0.63 * s
    chaise.box(
        (x_in + base_w / 2, (leg_h + base_top) / 2, zc),
        (base_w, base_top - leg_h, extra),
        color,
        mat,
    )
    chaise.box(
        (x_in + cw / 2, (base_top + seat_top) / 2, zc),
        (cw - 0.012, seat_top - base_top, extra - 0.012),
        shade(color, 1.12),
        mat,
    )
    chaise.box(
        (width / 2 - arm_w / 2, (leg_h + arm_top) / 2, zc),
        (arm_w, arm_top - leg_h, extra),
        color,
        mat,
    )
    chaise.box(
        (x_in + 0.03, leg_h / 2, z1 - 0.03), (0.05, leg_h, 0.05), color_rgb("dark brown"), WOOD
    )
    mesh = Mesh.concatenate([b.build().transformed(0.0, (0.0, 0.0, shift)), chaise.build()])
    main = Surface(seat.height, (seat.center[0], seat.center[1] + shift), seat.size)
    return ObjectModel(mesh, [main])


def build_stool(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A round seat on thin legs: a tall bar stool with a footrest, or a low three-legged one."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    bar = style.shape == "bar"
    seat_top = (0.74 if bar else 0.45) * s + float(rng.uniform(0.0, 0.03))
    radius, seat_t = (0.19 if bar else 0.16) * s, 0.05
    leg: Rgb = color if style.material == "wood" else color_rgb("dark gray")
    leg_mat = mat if style.material == "wood" else METAL
    b = MeshBuilder()
    b.cylinder((0.0, seat_top - seat_t, 0.0), radius, seat_t, color, mat)
    legs = 4 if bar else 3
    spread = 0.8 * radius
    for k in range(legs):
        angle = 2.0 * np.pi * (k + 0.5) / legs
        foot = (spread * np.cos(angle), 0.0, spread * np.sin(angle))
        b.cylinder(foot, 0.018, seat_top - seat_t, leg, leg_mat, 8, caps=False)
    if bar:
        a, y = spread / np.sqrt(2.0), 0.27 * s
        for sign in (-1.0, 1.0):
            b.box((0.0, y, sign * a), (2 * a, 0.02, 0.02), leg, leg_mat, faces="+y-y+z-z")
            b.box((sign * a, y, 0.0), (0.02, 0.02, 2 * a), leg, leg_mat, faces="+x-x+y-y")
    return ObjectModel(b.build())


def build_bench(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A long seat: a plank on two slab legs, or a padded top on four legs."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width = (1.1 + float(rng.uniform(0.0, 0.3))) * s
    depth, height = 0.38 * s, 0.46 * s
    b = MeshBuilder()
    if style.shape == "cushioned":
        pad = color_rgb(str(rng.choice(UPHOLSTERY_COLORS)))
        b.box((0.0, height - 0.04, 0.0), (width, 0.08, depth), pad, FABRIC)
        b.box((0.0, height - 0.1, 0.0), (width, 0.04, depth), color, mat)
        add_legs(b, width - 0.04, depth - 0.04, height - 0.12, 0.05, color, mat)
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])
    b.box((0.0, height - 0.025, 0.0), (width, 0.05, depth), color, mat)
    for sx in (-1.0, 1.0):
        slab = (0.05, height - 0.05, depth - 0.04)
        b.box(
            (sx * (width / 2 - 0.12), (height - 0.05) / 2, 0.0), slab, color, mat, faces="+x-x+z-z"
        )
    b.box((0.0, 0.15 * s, 0.0), (width - 0.29, 0.06, 0.04), color, mat, faces="+y-y+z-z")
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_ottoman(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A padded footstool, square on small feet or a round drum."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    height = (0.4 + float(rng.uniform(0.0, 0.05))) * s
    b = MeshBuilder()
    if style.shape == "round":
        radius = 0.28 * s
        b.cylinder((0.0, 0.0, 0.0), radius * 0.9, 0.04, color_rgb("dark brown"), WOOD)
        b.cylinder((0.0, 0.04, 0.0), radius, height - 0.06, color, mat)
        b.cylinder((0.0, height - 0.02, 0.0), radius, 0.02, shade(color, 1.12), mat)
        side = 1.3 * radius
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (side, side))])
    side = 0.55 * s
    add_legs(b, side - 0.04, side - 0.04, 0.05, 0.05, color_rgb("dark brown"), WOOD)
    b.box((0.0, (height - 0.04 + 0.05) / 2, 0.0), (side, height - 0.09, side), color, mat)
    b.box((0.0, height - 0.02, 0.0), (side - 0.01, 0.04, side - 0.01), shade(color, 1.12), mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (side, side))])


def build_beanbag(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A squashed sack; the chair variant has a raised back."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    radius = (0.42 + float(rng.uniform(0.0, 0.04))) * s
    b = MeshBuilder()
    squash = 0.5 if style.shape == "chair" else 0.62
    b.sphere((0.0, radius * squash, 0.0), radius, color, mat, 12, scale=(1.0, squash, 1.0))
    if style.shape == "chair":
        back = 0.7 * radius
        b.sphere(
            (0.0, radius * squash + 0.35 * back, -0.45 * radius),
            back,
            color,
            mat,
            10,
            scale=(1.1, 1.0, 0.6),
        )
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="chair",
        shapes={"straight-backed": "dining chair", "office": "office chair"},
        colors=(*WOOD_COLORS, "red", "blue"),
        materials=("wood", "plastic", "metal", "leather"),
        placement=Placement.AT_TABLE,
        rooms={
            "dining room": 4.0,
            "kitchen": 1.0,
            "study": 1.0,
            "bedroom": 0.5,
            "living room": 1.0,
        },
        build=build_chair,
    ),
    Category(
        name="armchair",
        shapes={"club": "armchair", "wingback": "wingback chair"},
        colors=UPHOLSTERY_COLORS,
        materials=("fabric", "leather"),
        placement=Placement.CORNER,
        rooms={"living room": 0.8, "bedroom": 0.2, "study": 0.3},
        build=build_armchair,
    ),
    Category(
        name="couch",
        shapes={"two-seat": "loveseat", "three-seat": "three-seat sofa", "L-shaped": "corner sofa"},
        colors=UPHOLSTERY_COLORS,
        materials=("fabric", "leather"),
        placement=Placement.AGAINST_WALL,
        rooms={"living room": 1.1, "study": 0.1, "bedroom": 0.05},
        build=build_sofa,
    ),
    Category(
        name="stool",
        shapes={"bar": "bar stool", "low": "stool"},
        colors=(*WOOD_COLORS, "red"),
        materials=("wood", "metal", "plastic", "leather"),
        placement=Placement.AT_TABLE,
        rooms={"kitchen": 1.0, "living room": 0.1, "storage room": 0.2, "bathroom": 0.1},
        build=build_stool,
    ),
    Category(
        name="bench",
        shapes={"slab": "bench", "cushioned": "cushioned bench"},
        colors=WOOD_COLORS,
        materials=("wood", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={"corridor": 0.5, "gym": 0.6, "dining room": 0.2, "bedroom": 0.2},
        build=build_bench,
    ),
    Category(
        name="ottoman",
        shapes={"square": "ottoman", "round": "round pouf"},
        colors=UPHOLSTERY_COLORS,
        materials=("fabric", "leather"),
        placement=Placement.FLOOR,
        rooms={"living room": 0.4, "bedroom": 0.2},
        build=build_ottoman,
    ),
    Category(
        name="beanbag",
        shapes={"round": "beanbag", "chair": "beanbag chair"},
        colors=(*UPHOLSTERY_COLORS, "orange", "pink", "yellow"),
        materials=("fabric", "leather"),
        placement=Placement.CORNER,
        rooms={"living room": 0.2, "bedroom": 0.2, "study": 0.1},
        build=build_beanbag,
    ),
]
