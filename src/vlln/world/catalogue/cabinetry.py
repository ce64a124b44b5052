"""Cabinet construction shared by furniture categories: finishes, legs, carcasses, fronts, tops.

Cabinets, tables, seats, beds and vanities are built from the same parts, so they share
proportions. Carcass fronts are recessed so that handles end inside the top's footprint: the
model's bounding box stays centred on the origin.
"""

from __future__ import annotations

from vlln.world.catalogue.base import Style
from vlln.world.catalogue.parts import shade
from vlln.world.materials import Rgb, color_rgb, material_index
from vlln.world.mesh import MeshBuilder

METAL = material_index("metal")
GLASS = material_index("glass")
PLAIN = material_index("plain")
GLASS_RGB: Rgb = (0.72, 0.84, 0.88)
MIRROR_RGB: Rgb = (0.84, 0.89, 0.92)  # lighter than any frame colour, so the glass reads
FRONT_T = 0.02  # thickness of drawer and door fronts
FRONT_RECESS = 0.05  # carcass front, behind the top's front edge: front + handle + 1 cm
WOOD_COLORS = ("brown", "dark brown", "beige", "white", "black", "gray")
PAINT_COLORS = ("white", "cream", "light gray", "gray", "dark green", "navy", "black", "beige")


def handle_rgb(body: Rgb) -> Rgb:
    """Handles contrast with their front: dark on light fronts, silver on dark ones."""
    return color_rgb("dark gray") if sum(body) / 3.0 > 0.5 else color_rgb("silver")


def add_legs(
    b: MeshBuilder,
    width: float,
    depth: float,
    height: float,
    thickness: float,
    color: Rgb,
    mat: int,
) -> None:
    """Four square legs whose outer faces are flush with a ``width`` x ``depth`` rectangle."""
    for sx in (-1.0, 1.0):
        for sz in (-1.0, 1.0):
            x = sx * (width / 2 - thickness / 2)
            z = sz * (depth / 2 - thickness / 2)
            size = (thickness, height, thickness)
            b.box((x, height / 2, z), size, color, mat, faces="+x-x+z-z")


def add_carcass(
    b: MeshBuilder,
    width: float,
    depth: float,
    y_range: tuple[float, float],
    color: Rgb,
    mat: int,
    x: float = 0.0,
) -> float:
    """A closed cabinet body between two heights; returns the z of its (recessed) front."""
    y0, y1 = y_range
    z_front = depth / 2 - FRONT_RECESS
    size = (width, y1 - y0, z_front + depth / 2)
    b.box((x, (y0 + y1) / 2, (z_front - depth / 2) / 2), size, color, mat)
    return z_front


def add_top(
    b: MeshBuilder, width: float, depth: float, y: float, thickness: float, color: Rgb, mat: int
) -> None:
    """A board whose upper face is at height ``y``, centred on the origin."""
    b.box((0.0, y - thickness / 2, 0.0), (width, thickness, depth), color, mat)


def add_fronts(
    b: MeshBuilder,
    x_range: tuple[float, float],
    y_range: tuple[float, float],
    z_front: float,
    grid: tuple[int, int],
    color: Rgb,
    mat: int,
    kind: str = "drawer",
) -> None:
    """A ``(columns, rows)`` grid of drawer or door fronts on the face ``z = z_front``.

    Drawers get a horizontal handle in their middle; doors a vertical one on the side that
    faces the middle of the grid, so a pair of doors looks like a pair.
    """
    (x0, x1), (y0, y1) = x_range, y_range
    cols, rows = grid
    cw, rh = (x1 - x0) / cols, (y1 - y0) / rows
    handle, panel = handle_rgb(color), shade(color, 1.08)
    hz = z_front + FRONT_T + 0.01
    for c in range(cols):
        cx = x0 + (c + 0.5) * cw
        for r in range(rows):
            cy = y0 + (r + 0.5) * rh
            size = (cw - 0.006, rh - 0.006, FRONT_T)
            b.box((cx, cy, z_front + FRONT_T / 2), size, panel, mat, faces="+x-x+y-y+z")
            if kind == "drawer":
                size = (min(0.16, 0.4 * cw), 0.015, 0.02)
                b.box((cx, cy + 0.15 * rh, hz), size, handle, METAL, faces="+x-x+y-y+z")
                continue
            side = 1.0 if cx <= (x0 + x1) / 2 + 1e-6 else -1.0
            hy = cy + 0.3 * rh if rh < 1.0 else cy
            size = (0.015, min(0.22, 0.4 * rh), 0.02)
            b.box((cx + side * (cw / 2 - 0.05), hy, hz), size, handle, METAL, faces="+x-x+y-y+z")


def add_framed_mirror(
    b: MeshBuilder, width: float, height: float, y0: float, z_back: float, frame: Rgb, mat: int
) -> None:
    """A rectangular mirror in a frame, its back on ``z = z_back``, its bottom at ``y0``."""
    b.box((0.0, y0 + height / 2, z_back + 0.0125), (width, height, 0.025), frame, mat)
    glass = (width - 0.08, height - 0.08, 0.005)
    b.box((0.0, y0 + height / 2, z_back + 0.0275), glass, MIRROR_RGB, GLASS, faces="+z")


def worktop_finish(style: Style) -> tuple[Rgb, int]:
    """Worktop colour and material: the style's material, in a colour that contrasts."""
    if style.material == "wood":
        return color_rgb("brown"), material_index("wood")
    light = sum(color_rgb(style.color)) / 3.0 > 0.5
    return color_rgb("dark gray" if light else "white"), material_index(style.material)
