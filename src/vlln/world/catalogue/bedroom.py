"""Bedroom furniture and textiles: beds, nightstands, cribs, pillows and rugs."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import (
    FRONT_RECESS,
    WOOD_COLORS,
    add_carcass,
    add_fronts,
    add_legs,
    add_top,
)
from vlln.world.catalogue.parts import shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

FABRIC = material_index("fabric")
BEDDING_COLORS = ("white", "light blue", "beige", "gray", "navy", "pink", "dark green", "cream")
TEXTILE_COLORS = (
    "white",
    "beige",
    "gray",
    "blue",
    "navy",
    "red",
    "green",
    "yellow",
    "pink",
    "orange",
    "cream",
)


def _signed_power(w: NDArray[np.float64], e: float) -> NDArray[np.float64]:
    return np.sign(w) * np.abs(w) ** e


def add_pillow(
    b: MeshBuilder,
    center: tuple[float, float, float],
    size: tuple[float, float, float],
    color: Rgb,
    mat: int,
) -> None:
    """A plump pillow of ``size`` (width, height, depth): a superellipsoid, square in plan.

    The squarish outline (exponent 0.3 around) with rounded, bulging faces (0.7 vertically) is
    what tells a pillow apart from a lens-shaped ellipsoid.
    """
    radii = np.asarray(size, np.float64) / 2
    around, updown = 0.3, 0.7
    lat = np.linspace(-np.pi / 2, np.pi / 2, 7)[:, None]
    lon = np.linspace(-np.pi, np.pi, 13)[None, :]
    cu, su, cv, sv = np.cos(lat), np.sin(lat), np.cos(lon), np.sin(lon)
    unit = np.stack(
        np.broadcast_arrays(
            _signed_power(cu, updown) * _signed_power(cv, around),
            _signed_power(su, updown),
            _signed_power(cu, updown) * _signed_power(sv, around),
        ),
        axis=-1,
    )
    normal = np.stack(
        np.broadcast_arrays(
            _signed_power(cu, 2 - updown) * _signed_power(cv, 2 - around) / radii[0],
            _signed_power(su, 2 - updown) / radii[1],
            _signed_power(cu, 2 - updown) * _signed_power(sv, 2 - around) / radii[2],
        ),
        axis=-1,
    )
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    points = unit * radii + np.asarray(center)
    corners = []
    for r in range(lat.shape[0] - 1):
        for c in range(lon.shape[1] - 1):
            a, b1, c1, d = (r, c), (r, c + 1), (r + 1, c + 1), (r + 1, c)
            if r > 0:  # the bottom pole row is a fan of triangles, not quads
                corners += [a, c1, b1]
            if r < lat.shape[0] - 2:
                corners += [a, d, c1]
    rows, cols = np.array(corners).T
    uv = np.stack([points[rows, cols, 0], points[rows, cols, 2]], axis=1)
    b.add_triangles(points[rows, cols], normal[rows, cols], uv, color, mat)


def build_bed(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Frame on short legs, headboard, mattress, duvet and pillows; the duvet top holds things."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    double = style.shape == "double"
    width, length = (1.65 if double else 0.95) * s, 2.05 * s
    head_t, head_h = 0.06, (1.0 + float(rng.uniform(0.0, 0.15))) * s
    leg_h, frame_top, mattress_top = 0.1 * s, 0.34 * s, 0.56 * s
    z_head, z_foot = -(length + head_t) / 2, (length + head_t) / 2 - 0.015
    zc = (z_head + head_t + z_foot) / 2
    white = color_rgb("white")
    bedding = color_rgb(str(rng.choice(BEDDING_COLORS)))
    b = MeshBuilder()
    b.box((0.0, head_h / 2, z_head + head_t / 2), (width + 0.04, head_h, head_t), color, mat)
    add_legs(b, width, length - head_t, leg_h, 0.06, color, mat)
    frame_len = z_foot - z_head - head_t
    b.box((0.0, (leg_h + frame_top) / 2, zc), (width, frame_top - leg_h, frame_len), color, mat)
    mattress = (width - 0.04, mattress_top - frame_top, frame_len - 0.04)
    b.box((0.0, (frame_top + mattress_top) / 2, zc), mattress, white, FABRIC)
    cover_z0, cover_t = z_head + head_t + 0.55 * s, 0.05
    cover_len = z_foot + 0.005 - cover_z0
    cover_y = mattress_top + cover_t / 2
    b.box(
        (0.0, cover_y, cover_z0 + cover_len / 2),
        (width + 0.02, cover_t, cover_len),
        bedding,
        FABRIC,
    )
    drape_y, drape_h = mattress_top + cover_t - 0.14 * s, 0.28 * s
    for sx in (-1.0, 1.0):
        side = (0.01, drape_h, cover_len)
        b.box((sx * (width / 2 + 0.005), drape_y, cover_z0 + cover_len / 2), side, bedding, FABRIC)
    front = (width + 0.02, drape_h, 0.01)
    b.box((0.0, drape_y, z_foot + 0.01), front, bedding, FABRIC)
    pillows = 2 if double else 1
    pw = min(0.65 * s, (width - 0.12) / pillows - 0.04)
    for k in range(pillows):
        x = -width / 2 + (k + 0.5) * width / pillows
        size = (pw, 0.13 * s, 0.36 * s)
        add_pillow(
            b, (x, mattress_top + 0.065 * s, z_head + head_t + 0.28 * s), size, white, FABRIC
        )
    top = Surface(mattress_top + cover_t, (0.0, cover_z0 + cover_len / 2), (width, cover_len))
    return ObjectModel(b.build(), [top])


def build_nightstand(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A small bedside cabinet: a drawer over an open niche on legs, or two drawers."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width, depth = 0.45 * s + float(rng.uniform(0.0, 0.05)), 0.4 * s
    height = 0.55 * s
    xs = (-width / 2, width / 2)
    b = MeshBuilder()
    add_top(b, width + 0.02, depth, height, 0.025, color, mat)
    if style.shape == "two-drawer":
        z_front = add_carcass(b, width, depth, (0.0, height - 0.025), color, mat)
        add_fronts(b, xs, (0.05, height - 0.03), z_front, (1, 2), color, mat)
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])
    leg_h = 0.12 * s
    add_legs(b, width - 0.02, depth - 2 * FRONT_RECESS, leg_h, 0.04, color, mat)
    z_front = add_carcass(b, width, depth, (leg_h, height - 0.025), color, mat)
    drawer_y0 = height - 0.03 - 0.14 * s
    add_fronts(b, xs, (drawer_y0, height - 0.03), z_front, (1, 1), color, mat)
    niche = (width - 0.05, drawer_y0 - leg_h - 0.04, 0.004)
    b.box(
        (0.0, (leg_h + drawer_y0) / 2, z_front + 0.002), niche, shade(color, 0.35), mat, faces="+z"
    )
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_crib(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A baby cot: four posts, top and bottom rails, vertical slats all round and a mattress."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    length, depth, height = 1.25 * s, 0.68 * s, (0.92 + float(rng.uniform(0.0, 0.06))) * s
    post, rail, base = 0.05, 0.04, 0.25 * s
    b = MeshBuilder()
    add_legs(b, length, depth, height, post, color, mat)
    hx, hz = length / 2 - post / 2, depth / 2 - post / 2
    for y in (base, height - rail / 2):
        for sz in (-1.0, 1.0):
            b.box((0.0, y, sz * hz), (length - 2 * post, rail, rail), color, mat)
        for sx in (-1.0, 1.0):
            b.box((sx * hx, y, 0.0), (rail, rail, depth - 2 * post), color, mat)
    slat_y0, slat_y1 = base + rail / 2, height - rail
    slat = (0.02, slat_y1 - slat_y0, 0.02)
    for span, along_x in ((length - 2 * post, True), (depth - 2 * post, False)):
        n = int(span / 0.13)
        for k in range(n):
            u = -span / 2 + (k + 0.5) * span / n
            for sign in (-1.0, 1.0):
                x, z = (u, sign * hz) if along_x else (sign * hx, u)
                b.box((x, (slat_y0 + slat_y1) / 2, z), slat, color, mat, faces="+x-x+z-z")
    mattress = (length - 2 * post, 0.1, depth - 2 * post)
    b.box((0.0, base + rail / 2 + 0.05, 0.0), mattress, color_rgb("white"), FABRIC)
    return ObjectModel(b.build())


def build_pillow(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A bed pillow (oblong) or a square throw pillow, lying flat."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    square = style.shape == "square"
    width = (0.42 if square else 0.62) * s + float(rng.uniform(0.0, 0.04))
    depth, height = (width if square else 0.4 * s), 0.14 * s
    b = MeshBuilder()
    add_pillow(b, (0.0, height / 2, 0.0), (width, height, depth), color, mat)
    return ObjectModel(b.build())


def build_rug(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A flat rug (a centimetre thick) with a darker border, rectangular, round or a runner."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    border = shade(color, 0.6)
    b = MeshBuilder()
    if style.shape == "round":
        radius = (0.7 + float(rng.uniform(0.0, 0.2))) * s
        b.cylinder((0.0, 0.0, 0.0), radius, 0.01, border, mat, 16)
        b.cylinder((0.0, 0.0, 0.0), radius - 0.1 * s, 0.012, color, mat, 16)
        return ObjectModel(b.build())
    if style.shape == "runner":
        width, depth = (2.2 + float(rng.uniform(0.0, 0.6))) * s, 0.75 * s
    else:
        width, depth = (1.8 + float(rng.uniform(0.0, 0.6))) * s, 1.3 * s
    b.box((0.0, 0.005, 0.0), (width, 0.01, depth), border, mat, faces="+x-x+y+z-z")
    inner = (width - 0.24 * s, 0.012, depth - 0.24 * s)
    b.box((0.0, 0.006, 0.0), inner, color, mat, faces="+y")
    return ObjectModel(b.build())


CATEGORIES: list[Category] = [
    Category(
        name="bed",
        shapes={"single": "single bed", "double": "double bed"},
        colors=(*WOOD_COLORS, "navy", "beige"),
        materials=("wood", "fabric", "leather", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 1.0},
        build=build_bed,
    ),
    Category(
        name="nightstand",
        shapes={"one-drawer": "nightstand", "two-drawer": "bedside cabinet"},
        colors=WOOD_COLORS,
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 1.4},
        build=build_nightstand,
    ),
    Category(
        name="crib",
        shapes={"slatted": "baby crib"},
        colors=("white", "beige", "brown", "gray", "light blue", "pink"),
        materials=("wood", "plain"),
        placement=Placement.AGAINST_WALL,
        rooms={"bedroom": 0.08},
        build=build_crib,
    ),
    Category(
        name="pillow",
        shapes={"oblong": "bed pillow", "square": "throw pillow"},
        colors=TEXTILE_COLORS,
        materials=("fabric", "leather"),
        placement=Placement.ON_SURFACE,
        rooms={"bedroom": 2.0, "living room": 1.5, "study": 0.1},
        build=build_pillow,
    ),
    Category(
        name="rug",
        shapes={"rectangular": "area rug", "round": "round rug", "runner": "runner rug"},
        colors=(*TEXTILE_COLORS, "teal", "purple", "dark gray"),
        materials=("carpet", "fabric"),
        placement=Placement.FLOOR,
        rooms={
            "living room": 0.7,
            "bedroom": 0.5,
            "dining room": 0.3,
            "study": 0.2,
            "corridor": 0.3,
        },
        build=build_rug,
    ),
]
