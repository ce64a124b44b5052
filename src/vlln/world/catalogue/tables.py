"""Tables and other furniture with a working top: dining tables, desks, islands, TV stands."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.cabinetry import (
    FRONT_RECESS,
    METAL,
    PAINT_COLORS,
    WOOD_COLORS,
    add_carcass,
    add_fronts,
    add_legs,
    add_top,
    worktop_finish,
)
from vlln.world.catalogue.parts import shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

TOP_T = 0.04  # thickness of a table top


def _leg_finish(style: Style) -> tuple[Rgb, int]:
    """Stone and glass tops stand on black metal legs; others on legs of their own material."""
    if style.material in ("marble", "glass"):
        return color_rgb("black"), METAL
    return color_rgb(style.color), material_index(style.material)


def _inscribed_square(radius: float) -> float:
    """Side of a square that fits inside a 12-sided round top of this radius."""
    return 1.3 * radius


def _pedestal_table(
    b: MeshBuilder, radius: float, height: float, style: Style, top: Rgb, top_mat: int
) -> Surface:
    """A round top on a central column and a spreading foot."""
    leg, leg_mat = _leg_finish(style)
    s = style.scale
    b.cylinder((0.0, height - TOP_T, 0.0), radius, TOP_T, top, top_mat)
    b.cylinder((0.0, 0.03, 0.0), 0.045 * s, height - TOP_T - 0.03, leg, leg_mat, 8, caps=False)
    b.cylinder((0.0, 0.0, 0.0), 0.55 * radius, 0.03, leg, leg_mat, 10, radius_top=0.4 * radius)
    side = _inscribed_square(radius)
    return Surface(height, (0.0, 0.0), (side, side))


def _apron(b: MeshBuilder, width: float, depth: float, y: float, color: Rgb, mat: int) -> None:
    """The frame under a table top that joins the legs (visible as a band below the edge)."""
    for sz in (-1.0, 1.0):
        b.box(
            (0.0, y - 0.04, sz * (depth / 2 - 0.01)),
            (width, 0.08, 0.02),
            color,
            mat,
            faces="+z-z-y",
        )
    for sx in (-1.0, 1.0):
        b.box(
            (sx * (width / 2 - 0.01), y - 0.04, 0.0),
            (0.02, 0.08, depth),
            color,
            mat,
            faces="+x-x-y",
        )


def build_table(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A dining table: rectangular or square on four legs, or round on a pedestal."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    height = 0.75 * s
    b = MeshBuilder()
    if style.shape == "round":
        radius = (0.5 + float(rng.uniform(0.0, 0.06))) * s
        top = _pedestal_table(b, radius, height, style, color, mat)
        return ObjectModel(b.build(), [top])
    if style.shape == "square":
        width = depth = (0.85 + float(rng.uniform(0.0, 0.1))) * s
    else:
        width, depth = (1.4 + float(rng.uniform(0.0, 0.25))) * s, 0.85 * s
    leg, leg_mat = _leg_finish(style)
    add_top(b, width, depth, height, TOP_T, color, mat)
    _apron(b, width - 0.1, depth - 0.1, height - TOP_T, leg, leg_mat)
    add_legs(b, width - 0.1, depth - 0.1, height - TOP_T, 0.06 * s, leg, leg_mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_coffee_table(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A low table: rectangular with a lower shelf, or round on three legs."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    leg, leg_mat = _leg_finish(style)
    height = (0.4 + float(rng.uniform(0.0, 0.05))) * s
    b = MeshBuilder()
    if style.shape == "round":
        radius = 0.42 * s
        b.cylinder((0.0, height - TOP_T, 0.0), radius, TOP_T, color, mat)
        for k in range(3):
            angle = 2.0 * np.pi * k / 3 + np.pi / 2
            foot = (0.7 * radius * np.cos(angle), 0.0, 0.7 * radius * np.sin(angle))
            b.cylinder(foot, 0.025, height - TOP_T, leg, leg_mat, 8, caps=False)
        side = _inscribed_square(radius)
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (side, side))])
    width, depth = 1.1 * s, 0.6 * s
    add_top(b, width, depth, height, TOP_T, color, mat)
    add_legs(b, width - 0.04, depth - 0.04, height - TOP_T, 0.05, leg, leg_mat)
    add_top(b, width - 0.12, depth - 0.06, 0.14 * s, 0.02, shade(color, 0.85), mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_desk(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A writing desk on legs with a drawer, or a desk with a drawer pedestal and side panel."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width = (1.2 + float(rng.uniform(0.0, 0.2))) * s
    depth, height = 0.62 * s, 0.75 * s
    under = height - TOP_T
    b = MeshBuilder()
    add_top(b, width, depth, height, TOP_T, color, mat)
    if style.shape == "pedestal":
        ped_w = 0.42 * s
        xp = width / 2 - ped_w / 2
        b.box((-width / 2 + 0.015, under / 2, 0.0), (0.03, under, depth), color, mat)
        b.box((0.0, under - 0.2, -depth / 2 + 0.02), (width - 0.06, 0.35, 0.015), color, mat)
        z_front = add_carcass(b, ped_w, depth, (0.0, under), color, mat, x=xp)
        xs = (xp - ped_w / 2, xp + ped_w / 2)
        add_fronts(b, xs, (0.02, under - 0.01), z_front, (1, 3), color, mat)
    else:
        add_legs(b, width - 0.04, depth - 0.04, under, 0.05 * s, color, mat)
        z_front = depth / 2 - FRONT_RECESS
        housing = (0.56 * s, 0.12, z_front + depth / 2 - 0.04)
        b.box(
            (0.0, under - 0.06, (z_front - depth / 2 + 0.04) / 2),
            housing,
            color,
            mat,
            faces="+x-x-y",
        )
        add_fronts(b, (-0.28 * s, 0.28 * s), (under - 0.12, under), z_front, (1, 1), color, mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


def build_side_table(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A small table: square on legs with a lower shelf, or round on a pedestal."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    height = (0.55 + float(rng.uniform(0.0, 0.06))) * s
    b = MeshBuilder()
    if style.shape == "round":
        top = _pedestal_table(b, 0.26 * s, height, style, color, mat)
        return ObjectModel(b.build(), [top])
    leg, leg_mat = _leg_finish(style)
    side = 0.45 * s
    add_top(b, side, side, height, 0.03, color, mat)
    add_legs(b, side - 0.03, side - 0.03, height - 0.03, 0.04, leg, leg_mat)
    add_top(b, side - 0.06, side - 0.06, 0.15 * s, 0.02, color, mat)
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (side, side))])


def build_kitchen_island(style: Style, rng: np.random.Generator) -> ObjectModel:
    """Base cabinets under a worktop, free-standing; the breakfast bar overhangs at the back."""
    s = style.scale
    color = color_rgb(style.color)
    front_mat = material_index("wood" if style.material == "wood" else "plain")
    width = (1.5 + float(rng.uniform(0.0, 0.3))) * s
    depth, height, plinth = 0.8 * s, 0.92 * s, 0.1 * s
    overhang = 0.35 * s if style.shape == "with overhang" else 0.0
    top_rgb, top_mat = worktop_finish(style)
    b = MeshBuilder()
    b.box(
        (0.0, plinth / 2, -0.02),
        (width - 0.1, plinth, depth - 0.14),
        color_rgb("black"),
        front_mat,
        faces="+x-x+z-z",
    )
    z_front = add_carcass(b, width - 0.04, depth, (plinth, height - 0.04), color, front_mat)
    b.box((0.0, height - 0.02, -overhang / 2), (width, 0.04, depth + overhang), top_rgb, top_mat)
    xs, fy1 = (-width / 2 + 0.02, width / 2 - 0.02), height - 0.045
    cols = round(width / 0.5)
    add_fronts(b, xs, (fy1 - 0.16 * s, fy1), z_front, (cols, 1), color, front_mat)
    add_fronts(b, xs, (plinth, fy1 - 0.16 * s), z_front, (cols, 1), color, front_mat, "door")
    mesh = b.build().transformed(0.0, (0.0, 0.0, overhang / 2))
    return ObjectModel(mesh, [Surface(height, (0.0, 0.0), (width, depth + overhang))])


def build_tv_stand(style: Style, rng: np.random.Generator) -> ObjectModel:
    """A long low cabinet with an open middle niche, or an open two-shelf stand."""
    s = style.scale
    color, mat = color_rgb(style.color), material_index(style.material)
    width = (1.4 + float(rng.uniform(0.0, 0.3))) * s
    depth, height = 0.4 * s, 0.5 * s
    b = MeshBuilder()
    if style.shape == "open":
        t = 0.03
        for sx in (-1.0, 1.0):
            b.box((sx * (width / 2 - t / 2), height / 2, 0.0), (t, height, depth), color, mat)
        for y in (0.06 * s, height / 2, height):
            b.box((0.0, y - t / 2, 0.0), (width - 2 * t, t, depth), color, mat)
        shelf = Surface(height / 2, (0.0, 0.0), (width - 2 * t, depth))
        return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth)), shelf])
    leg_h = 0.08 * s
    add_legs(b, width - 0.06, depth - 2 * FRONT_RECESS, leg_h, 0.04, color_rgb("black"), METAL)
    z_front = add_carcass(b, width, depth, (leg_h, height - 0.025), color, mat)
    add_top(b, width + 0.02, depth, height, 0.025, color, mat)
    third, fy = width / 3, (leg_h + 0.005, height - 0.03)
    add_fronts(b, (-width / 2, -third / 2), fy, z_front, (1, 1), color, mat, "door")
    add_fronts(b, (third / 2, width / 2), fy, z_front, (1, 1), color, mat, "door")
    niche = (third - 0.04, fy[1] - fy[0] - 0.04, 0.004)
    b.box((0.0, (fy[0] + fy[1]) / 2, z_front + 0.002), niche, shade(color, 0.3), mat, faces="+z")
    return ObjectModel(b.build(), [Surface(height, (0.0, 0.0), (width, depth))])


CATEGORIES: list[Category] = [
    Category(
        name="table",
        shapes={"rectangular": "dining table", "round": "round table", "square": "square table"},
        colors=WOOD_COLORS,
        materials=("wood", "marble", "metal", "plastic"),
        placement=Placement.FLOOR,
        rooms={"dining room": 1.0, "kitchen": 0.5, "living room": 0.2, "study": 0.2},
        build=build_table,
    ),
    Category(
        name="coffee table",
        shapes={"rectangular": "coffee table", "round": "round coffee table"},
        colors=WOOD_COLORS,
        materials=("wood", "glass", "marble", "metal"),
        placement=Placement.FLOOR,
        rooms={"living room": 0.9},
        build=build_coffee_table,
    ),
    Category(
        name="desk",
        shapes={"writing": "writing desk", "pedestal": "office desk"},
        colors=WOOD_COLORS,
        materials=("wood", "plain", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={"study": 1.0, "bedroom": 0.4, "living room": 0.1},
        build=build_desk,
    ),
    Category(
        name="side table",
        shapes={"square": "end table", "round": "round side table"},
        colors=WOOD_COLORS,
        materials=("wood", "marble", "metal", "glass"),
        placement=Placement.CORNER,
        rooms={"living room": 0.8, "bedroom": 0.2, "corridor": 0.2},
        build=build_side_table,
    ),
    Category(
        name="kitchen island",
        shapes={"cabinet": "kitchen island", "with overhang": "breakfast bar"},
        colors=PAINT_COLORS,
        materials=("marble", "wood", "plastic"),
        placement=Placement.FLOOR,
        rooms={"kitchen": 0.4},
        build=build_kitchen_island,
    ),
    Category(
        name="tv stand",
        shapes={"cabinet": "tv cabinet", "open": "open tv stand"},
        colors=WOOD_COLORS,
        materials=("wood", "plain", "metal"),
        placement=Placement.AGAINST_WALL,
        rooms={"living room": 0.8, "bedroom": 0.2},
        build=build_tv_stand,
    ),
]
