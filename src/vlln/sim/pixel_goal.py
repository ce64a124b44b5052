"""Pixel goals: from a pixel of a (tilted) frame to a navigable floor point.

A model that looked down picks the pixel it wants to walk to. The pixel's z-depth and the
camera pose (feet position, yaw, tilt; :meth:`CameraSpec.unproject`) give the world point it
shows; its floor-plan position is then snapped to the nearest navigable cell, because a pixel
on a rug edge, a chair leg or a wall foot still means "go there". Pixels where nothing was
drawn (depth 0) or that lie outside the image give no goal.

In a house with several storeys the point is snapped onto the storey the agent is on (its
floor, or the flight of stairs it shares with the next storey) and keeps that storey's walking
height there, so a pixel on the stairs ahead means a point up (or down) the flight.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from vlln.sim.agent import AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.navgrid import NavGrid
from vlln.sim.storeys import Point3, Storeys

Point2 = tuple[float, float]


def pixel_world_point(
    spec: CameraSpec, depth: NDArray[np.floating], col: int, row: int, state: AgentState
) -> NDArray[np.float64] | None:
    """The world point that pixel ``(col, row)`` of a frame taken at ``state`` shows, or None
    when the pixel is outside the image or shows nothing (z-depth 0 or not finite)."""
    if not (0 <= col < spec.width and 0 <= row < spec.height):
        return None
    z_depth = float(depth[row, col])
    if not (math.isfinite(z_depth) and z_depth > 0.0):
        return None
    return spec.unproject(col, row, z_depth, state.position, state.yaw, state.tilt)


def pixel_floor_goal(
    spec: CameraSpec,
    grid: NavGrid | Storeys,
    depth: NDArray[np.floating],
    col: int,
    row: int,
    state: AgentState,
) -> Point2 | Point3 | None:
    """The navigable floor point nearest to what pixel ``(col, row)`` shows (module doc):
    ``(x, z)`` on a :class:`NavGrid`, ``(x, y, z)`` on the agent's storey of :class:`Storeys`."""
    point = pixel_world_point(spec, depth, col, row, state)
    if point is None:
        return None
    if isinstance(grid, Storeys):
        return grid.snap_point(float(point[0]), state.position[1], float(point[2]))
    return grid.snap_point(float(point[0]), float(point[2]))
