"""Where the collector walks: one storey's grid, or the storeys of a house joined by stairs.

The collector names places as ``(x, y, z)`` everywhere; ``y`` is the walking height, which
names the storey. On one storey every place has the start's height and the fields are the
simulator's one-storey geodesic fields, so a one-storey walk is what it always was.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.simulator import Simulator
from vlln.sim.storey_field import StoreyField
from vlln.sim.storeys import Point3, Storeys
from vlln.world.frame import yaw_of

# The agent stands on a storey's floor when its height is this close to it (else on stairs).
_ON_FLOOR = 0.02
_AROUND = 1.5  # m; the floor around a landing that tells which way the storey opens


class Ground:
    """Points, snapping and distance fields on the house's navigable area."""

    def __init__(self, sim: Simulator, start_y: float) -> None:
        self.sim = sim
        self.storeys: Storeys | None = sim.storeys
        self.nav: NavGrid | Storeys = sim.nav
        self._start_y = start_y

    @property
    def levels(self) -> int:
        return 1 if self.storeys is None else len(self.storeys.grids)

    def level(self, y: float) -> int:
        """The storey of a height (the one whose floor is nearest)."""
        return 0 if self.storeys is None else self.storeys.level_of(y)

    def floor_y(self, level: int) -> float:
        return self._start_y if self.storeys is None else self.storeys.floor_ys[level]

    def on_floor(self, y: float) -> bool:
        """Whether the height is on a storey's floor rather than part-way up a flight."""
        return abs(y - self.floor_y(self.level(y))) <= _ON_FLOOR

    def point(self, position: Sequence[float]) -> Point3:
        """A place given as ``(x, y, z)``, or as ``(x, z)`` on one storey."""
        if len(position) == 2:
            return float(position[0]), self._start_y, float(position[1])
        x, y, z = position
        return float(x), float(y) if self.storeys is not None else self._start_y, float(z)

    def snap(self, x: float, y: float, z: float) -> Point3:
        """The nearest navigable cell centre on the storey of ``y``."""
        if self.storeys is None:
            sx, sz = self.sim.grid.snap_point(x, z)
            return sx, self._start_y, sz
        return self.storeys.snap_point(x, y, z)

    def field(self, goals: Sequence[Point3]) -> GeodesicField | StoreyField:
        """The (cached) distance field to the goals."""
        if self.storeys is None:
            return self.sim.geodesic_field([(x, z) for x, _, z in goals])
        return self.sim.distance_field(goals)

    @staticmethod
    def distance(field: GeodesicField | StoreyField, point: Sequence[float]) -> float:
        x, y, z = point
        return field.distance(x, z, y)

    def open_heading(self, position: Point3) -> float | None:
        """The yaw toward the middle of the storey's floor (treads left out) within 1.5 m:
        from a flight's landing, the way the storey opens up. None on one storey."""
        if self.storeys is None:
            return None
        x, y, z = position
        level = self.level(y)
        grid = self.storeys.grids[level]
        row, col = grid.world_to_cell(x, z)
        k = math.ceil(_AROUND / grid.cell_size)
        r0, c0 = max(row - k, 0), max(col - k, 0)
        floor = self.storeys.heights[level][r0 : row + k + 1, c0 : col + k + 1] == self.floor_y(
            level
        )
        rows, cols = np.nonzero(grid.navigable[r0 : row + k + 1, c0 : col + k + 1] & floor)
        dx = grid.origin[0] + (c0 + cols + 0.5) * grid.cell_size - x
        dz = grid.origin[1] + (r0 + rows + 0.5) * grid.cell_size - z
        near = np.hypot(dx, dz) <= _AROUND
        if not near.any():
            return None
        return yaw_of(float(dx[near].mean()), float(dz[near].mean()))
