"""Goal view points of an object: where an agent may stop and count as having found it.

The benchmark takes every navigable point inside the object's 3-D box expanded by 0.6 m on
all sides. On one storey that is the navigable cells whose centres lie in the floor-plan
footprint of the expanded box; success is then a geodesic distance below 0.25 m to any of
them.
"""

from __future__ import annotations

import math

import numpy as np

from vlln.errors import ConfigError
from vlln.sim.navgrid import NavGrid, Point2
from vlln.sim.storeys import Point3, Storeys
from vlln.world.model import Box3

VIEW_POINT_MARGIN = 0.6
# A goal view point: (x, z) on one storey, (x, y, z) in a house with several.
GoalPoint = tuple[float, float] | tuple[float, float, float]


def view_points(
    grid: NavGrid, box: Box3, margin: float = VIEW_POINT_MARGIN, stride: int = 1
) -> list[Point2]:
    """Navigable cell centres inside the box's footprint grown by ``margin``, row by row.

    ``stride`` keeps only cells whose row and column are multiples of it (grid indices, so
    the choice does not depend on the box): fewer goals for the same coverage.
    """
    if not margin >= 0.0:
        raise ConfigError(f"margin must be >= 0 metres, got {margin}")
    if stride < 1:
        raise ConfigError(f"stride must be a positive integer, got {stride}")
    ox, oz = grid.origin
    s = grid.cell_size
    rows, cols = grid.shape
    x_lo, x_hi = box.min[0] - margin, box.max[0] + margin
    z_lo, z_hi = box.min[2] - margin, box.max[2] + margin
    # Cells whose centre (o + (i + 0.5) s) lies in [lo, hi].
    c0 = max(0, math.ceil((x_lo - ox) / s - 0.5))
    c1 = min(cols - 1, math.floor((x_hi - ox) / s - 0.5))
    r0 = max(0, math.ceil((z_lo - oz) / s - 0.5))
    r1 = min(rows - 1, math.floor((z_hi - oz) / s - 0.5))
    if c0 > c1 or r0 > r1:
        return []
    c0 += -c0 % stride
    r0 += -r0 % stride
    window = grid.navigable[r0 : r1 + 1 : stride, c0 : c1 + 1 : stride]
    points: list[Point2] = []
    for r, c in np.argwhere(window).tolist():
        x, z = grid.cell_to_world(r0 + r * stride, c0 + c * stride)
        # Guard the boundary against rounding in the index arithmetic above.
        if x_lo <= x <= x_hi and z_lo <= z <= z_hi:
            points.append((x, z))
    return points


def storey_view_points(
    storeys: Storeys, box: Box3, margin: float = VIEW_POINT_MARGIN, stride: int = 1
) -> list[Point3]:
    """:func:`view_points` on the storey the box stands on, with each point's height; on
    stairs only the points within ``margin`` of the box's height range are kept (the box is
    grown in 3-D), while the storey's floor always counts (for objects on a wall)."""
    level = storeys.level_under(box.min[1])
    grid = storeys.grids[level]
    floor = storeys.floor_ys[level]
    low, high = box.min[1] - margin, box.max[1] + margin
    points = [
        (x, storeys.height_at(level, x, z), z) for x, z in view_points(grid, box, margin, stride)
    ]
    return [p for p in points if p[1] == floor or low <= p[1] <= high]
