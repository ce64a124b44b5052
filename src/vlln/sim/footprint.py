"""Rasterising triangle footprints onto a navigation grid, vectorised over all triangles.

Two questions are asked of a triangle soup, both exactly (no sampling, so thin and vertical
faces are never missed):

* which cell centres lie on a floor triangle's floor-plan projection (walkable cells);
* which cell columns, cut to a height band, a triangle meets (blocked cells). This is a
  triangle/box overlap test by separating axes (Akenine-Möller), with the box being the cell
  column between the band's bottom and top.

Work is done per (triangle, candidate cell) pair in numpy; candidate cells are those under the
bounding box of the part of the triangle inside the band.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

Point2 = tuple[float, float]
BoolGrid = NDArray[np.bool_]
IntArray = NDArray[np.int64]
FloatArray = NDArray[np.float64]

# Geometry closer than this (metres) to a cell column still counts as touching it.
_TOUCH = 1e-9


def floor_cells(
    triangles: FloatArray, origin: Point2, cell_size: float, shape: tuple[int, int]
) -> BoolGrid:
    """Cells whose centre lies inside (or on the edge of) a triangle's floor-plan projection.

    Scanline fill: for every (triangle, row) the triangle's x-interval at the row's centre
    line, marked with a difference array, so the cost follows the rows, not the area.
    """
    rows_n, cols_n = shape
    ox, oz = origin
    xz = triangles[:, :, [0, 2]]
    r0 = np.ceil((xz[:, :, 1].min(axis=1) - oz) / cell_size - 0.5).astype(np.int64)
    r1 = np.floor((xz[:, :, 1].max(axis=1) - oz) / cell_size - 0.5).astype(np.int64)
    zero = np.zeros_like(r0)
    tri, rows, _ = _candidate_cells(zero, zero, r0, r1, (rows_n, 1))
    z = oz + (rows + 0.5) * cell_size
    x_lo = np.full(len(tri), np.inf)
    x_hi = np.full(len(tri), -np.inf)
    for k in range(3):
        a, b = xz[tri, k], xz[tri, (k + 1) % 3]
        dz = b[:, 1] - a[:, 1]
        flat = dz == 0.0
        t = (z - a[:, 1]) / np.where(flat, 1.0, dz)
        crossing = ~flat & (t >= 0.0) & (t <= 1.0)
        x = a[:, 0] + t * (b[:, 0] - a[:, 0])
        x_lo = np.where(crossing, np.minimum(x_lo, x), x_lo)
        x_hi = np.where(crossing, np.maximum(x_hi, x), x_hi)
        on_edge = flat & (a[:, 1] == z)
        for end in (a, b):
            x_lo = np.where(on_edge, np.minimum(x_lo, end[:, 0]), x_lo)
            x_hi = np.where(on_edge, np.maximum(x_hi, end[:, 0]), x_hi)
    hit = x_lo <= x_hi
    # Centres on a shared edge must not fall between two triangles through rounding.
    c0 = np.ceil((x_lo[hit] - _TOUCH - ox) / cell_size - 0.5).astype(np.int64)
    c1 = np.floor((x_hi[hit] + _TOUCH - ox) / cell_size - 0.5).astype(np.int64)
    rows = rows[hit]
    c0, c1 = np.maximum(c0, 0), np.minimum(c1, cols_n - 1)
    span = c0 <= c1
    marks = np.zeros((rows_n, cols_n + 1), np.int32)
    np.add.at(marks, (rows[span], c0[span]), 1)
    np.add.at(marks, (rows[span], c1[span] + 1), -1)
    return np.cumsum(marks, axis=1)[:, :cols_n] > 0


def obstacle_cells(
    triangles: FloatArray,
    instance_ids: NDArray[np.int64],
    band: tuple[float, float],
    origin: Point2,
    cell_size: float,
    shape: tuple[int, int],
) -> BoolGrid:
    """Cells whose column meets a triangle in ``band = (bottom, top]``.

    Cells enclosed by the footprint of a single object (instance id >= 1) are blocked too:
    nothing can reach them, and they would otherwise be spurious islands inside furniture.
    """
    bottom, top = band
    heights = triangles[:, :, 1]
    keep = (heights.min(axis=1) <= top) & (heights.max(axis=1) > bottom)
    triangles, instance_ids = triangles[keep], instance_ids[keep]
    grid = np.zeros(shape, bool)
    if len(triangles) == 0:
        return grid
    low, high = _band_bounds(triangles, bottom, top)
    ox, oz = origin
    c0 = np.floor((low[:, 0] - ox) / cell_size).astype(np.int64)
    c1 = np.floor((high[:, 0] - ox) / cell_size).astype(np.int64)
    r0 = np.floor((low[:, 1] - oz) / cell_size).astype(np.int64)
    r1 = np.floor((high[:, 1] - oz) / cell_size).astype(np.int64)
    single = (c0 == c1) & (r0 == r1)
    # A triangle inside one column reaches into the band there (it spans the band's heights).
    one = single & (c0 >= 0) & (c0 < shape[1]) & (r0 >= 0) & (r0 < shape[0])
    hit_rows = [r0[one]]
    hit_cols = [c0[one]]
    hit_ids = [instance_ids[one]]
    multi = ~single
    if multi.any():
        tri, rows, cols = _candidate_cells(c0[multi], c1[multi], r0[multi], r1[multi], shape)
        meets = _overlaps_columns(triangles[multi], tri, rows, cols, band, origin, cell_size)
        hit_rows.append(rows[meets])
        hit_cols.append(cols[meets])
        hit_ids.append(instance_ids[multi][tri[meets]])
    rows = np.concatenate(hit_rows)
    cols = np.concatenate(hit_cols)
    ids = np.concatenate(hit_ids)
    grid[rows, cols] = True
    _fill_enclosed(grid, rows, cols, ids)
    return grid


def _candidate_cells(
    c0: IntArray, c1: IntArray, r0: IntArray, r1: IntArray, shape: tuple[int, int]
) -> tuple[IntArray, IntArray, IntArray]:
    """All ``(triangle, row, col)`` with the cell in the triangle's inclusive index box."""
    rows_n, cols_n = shape
    c0, c1 = np.maximum(c0, 0), np.minimum(c1, cols_n - 1)
    r0, r1 = np.maximum(r0, 0), np.minimum(r1, rows_n - 1)
    width = np.maximum(c1 - c0 + 1, 0)
    height = np.maximum(r1 - r0 + 1, 0)
    count = width * height
    tri = np.repeat(np.arange(len(count)), count)
    start = np.cumsum(count) - count
    local = np.arange(int(count.sum())) - np.repeat(start, count)
    w = width[tri]
    return tri, r0[tri] + local // w, c0[tri] + local % w


def _band_bounds(triangles: FloatArray, bottom: float, top: float) -> tuple[FloatArray, FloatArray]:
    """Floor-plan bounding box ``(min_xz, max_xz)`` of each triangle's part inside the band.

    That part is the convex hull of the vertices inside the band and the points where edges
    cross the band's bottom and top planes.
    """
    points: list[FloatArray] = []
    valid: list[NDArray[np.bool_]] = []
    y = triangles[:, :, 1]
    for k in range(3):
        points.append(triangles[:, k, :][:, [0, 2]])
        valid.append((y[:, k] >= bottom) & (y[:, k] <= top))
    for k in range(3):
        a, b = triangles[:, k, :], triangles[:, (k + 1) % 3, :]
        for plane in (bottom, top):
            crosses = (a[:, 1] - plane) * (b[:, 1] - plane) < 0.0
            dy = np.where(crosses, b[:, 1] - a[:, 1], 1.0)
            t = np.where(crosses, (plane - a[:, 1]) / dy, 0.0)[:, None]
            points.append((a + t * (b - a))[:, [0, 2]])
            valid.append(crosses)
    xz = np.stack(points, axis=1)
    mask = np.stack(valid, axis=1)[:, :, None]
    low = np.where(mask, xz, np.inf).min(axis=1)
    high = np.where(mask, xz, -np.inf).max(axis=1)
    return low, high


def _overlaps_columns(
    triangles: FloatArray,
    tri: IntArray,
    rows: IntArray,
    cols: IntArray,
    band: tuple[float, float],
    origin: Point2,
    cell_size: float,
) -> NDArray[np.bool_]:
    """Separating-axis test of each (triangle, cell column) pair.

    The box axes x and z are already satisfied by the candidate selection and y by the band
    filter, so the remaining axes are the triangle normal and the nine edge-by-box-axis
    cross products.
    """
    bottom, top = band
    half = np.array([cell_size / 2.0, (top - bottom) / 2.0, cell_size / 2.0])
    y_centre = (bottom + top) / 2.0
    v0, v1, v2 = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    edges = (v1 - v0, v2 - v1, v0 - v2)
    axes = [np.cross(edges[0], v2 - v0)]
    for e in edges:
        zero = np.zeros(len(e))
        axes.append(np.stack([zero, e[:, 2], -e[:, 1]], axis=1))  # e x unit-x
        axes.append(np.stack([-e[:, 2], zero, e[:, 0]], axis=1))  # e x unit-y
        axes.append(np.stack([e[:, 1], -e[:, 0], zero], axis=1))  # e x unit-z
    axis = np.stack(axes)  # (10, T, 3)
    projection = np.einsum("atd,tkd->atk", axis, triangles, optimize=True)  # (10, T, 3)
    shift = axis[:, :, 1] * y_centre
    # Per axis and triangle: the projected interval, widened by the box's projected radius.
    reach = np.abs(axis) @ half + _TOUCH
    low = np.ascontiguousarray(projection.min(axis=2) - shift - reach)
    high = np.ascontiguousarray(projection.max(axis=2) - shift + reach)
    ax = np.ascontiguousarray(axis[:, :, 0])
    az = np.ascontiguousarray(axis[:, :, 2])
    cx = origin[0] + (cols + 0.5) * cell_size
    cz = origin[1] + (rows + 0.5) * cell_size
    meets = np.ones(len(tri), bool)
    for k in range(len(axes)):
        centre = np.take(ax[k], tri) * cx + np.take(az[k], tri) * cz
        meets &= (np.take(low[k], tri) <= centre) & (np.take(high[k], tri) >= centre)
    return meets


def _fill_enclosed(grid: BoolGrid, rows: IntArray, cols: IntArray, ids: IntArray) -> None:
    """Block the cells that one object's footprint encloses."""
    objects = ids >= 1
    rows, cols, ids = rows[objects], cols[objects], ids[objects]
    if len(ids) == 0:
        return
    order = np.argsort(ids, kind="stable")
    rows, cols, ids = rows[order], cols[order], ids[order]
    bounds = np.flatnonzero(np.diff(ids)) + 1
    for r, c in zip(np.split(rows, bounds), np.split(cols, bounds), strict=True):
        r_lo, c_lo = int(r.min()), int(c.min())
        height, width = int(r.max()) - r_lo + 1, int(c.max()) - c_lo + 1
        if height < 3 or width < 3:
            continue
        mask = np.zeros((height, width), bool)
        mask[r - r_lo, c - c_lo] = True
        grid[r_lo : r_lo + height, c_lo : c_lo + width] |= ndimage.binary_fill_holes(mask)
