"""VLFM's value map: each frame's value painted onto the map cells the camera sees.

As in VLFM (Yokoyama et al., 2024), a frame's value goes to every cell in the camera's
field of view, up to what the depth shows in each image column, with a confidence that falls
from 1 on the optical axis to 0 at the image border (``cos²`` of the angle scaled to the half
field of view). A cell seen again keeps the confidence-weighted mean of its values, and its
confidence becomes ``(c_old² + c_new²) / (c_old + c_new)``, so a glimpse from the image
border barely changes what was seen head-on.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.mapping import ObstacleMap, Pose

_COLUMN_STRIDE = 8  # image columns per ray
_MAX_RANGE = 5.0  # metres: values are painted no farther than this


class ValueMap:
    """Value and confidence per cell of one storey's :class:`ObstacleMap`."""

    def __init__(self, obstacle_map: ObstacleMap, default: float) -> None:
        self.map = obstacle_map
        self.default = default  # the value of a cell never seen
        self.value = np.full(obstacle_map.shape, default, np.float32)
        self.confidence = np.zeros(obstacle_map.shape, np.float32)
        camera = obstacle_map.camera
        us = np.arange(_COLUMN_STRIDE // 2, camera.width, _COLUMN_STRIDE)
        rays = camera.pixel_ray(us, np.full(us.shape, camera.height / 2.0))
        self._columns = us
        self._slope = rays[:, 0]  # camera-frame x per metre ahead
        half = math.radians(camera.hfov_deg) / 2.0
        angle = np.arctan(self._slope)
        self._weight = np.cos(np.clip(angle / half, -1.0, 1.0) * math.pi / 2.0) ** 2
        self._steps = np.arange(0.0, _MAX_RANGE, obstacle_map.cell_size * 0.7)

    def add_frame(self, depth: NDArray[np.float32], pose: Pose, value: float) -> None:
        """Paint ``value`` over what a level camera at ``pose`` sees (``depth`` in metres)."""
        camera = self.map.camera
        row = np.asarray(depth)[camera.height // 2, self._columns].astype(np.float64)
        reach = np.where(row > 0.0, np.minimum(row, _MAX_RANGE), _MAX_RANGE)
        norm = np.hypot(self._slope, 1.0)
        sin, cos = math.sin(pose.yaw), math.cos(pose.yaw)
        # camera right is (cos, -sin), ahead is (-sin, -cos) on the floor plan (world.frame)
        dx = (self._slope * cos - sin) / norm
        dz = (-self._slope * sin - cos) / norm
        distance = self._steps[None, :] * np.ones((self._columns.size, 1))
        inside = distance <= (reach * norm)[:, None]  # depth is along the axis, not the ray
        x = pose.x + dx[:, None] * distance
        z = pose.z + dz[:, None] * distance
        weight = np.broadcast_to(self._weight[:, None], distance.shape)
        cells, weights = self._cells_with_weights(x[inside], z[inside], weight[inside])
        self._fuse(cells, weights, value)

    def _cells_with_weights(
        self, x: NDArray[np.float64], z: NDArray[np.float64], weight: NDArray[np.float64]
    ) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
        """Flat cell index and confidence of each point on the map."""
        rows, cols = self.map.shape
        s, (ox, oz) = self.map.cell_size, self.map.origin
        col = np.floor((x - ox) / s).astype(np.intp)
        row = np.floor((z - oz) / s).astype(np.intp)
        on = (row >= 0) & (row < rows) & (col >= 0) & (col < cols)
        return row[on] * cols + col[on], weight[on]

    def _fuse(self, cells: NDArray[np.intp], weights: NDArray[np.float64], value: float) -> None:
        if cells.size == 0:
            return
        best = np.zeros(self.value.size, np.float64)
        np.maximum.at(best, cells, weights)  # a cell takes its most central ray's confidence
        unique = np.unique(cells)
        new = best[unique]
        flat_value = self.value.reshape(-1)
        flat_conf = self.confidence.reshape(-1)
        old = flat_conf[unique].astype(np.float64)
        total = np.maximum(old + new, 1e-9)
        flat_value[unique] = (old * flat_value[unique] + new * value) / total
        flat_conf[unique] = (old * old + new * new) / total

    def around(self, x: float, z: float, radius: float = 0.5) -> float:
        """Confidence-weighted mean value within ``radius`` of a point (the default where
        nothing there was seen)."""
        row, col = self.map.cell_of(x, z)
        k = max(1, math.ceil(radius / self.map.cell_size))
        window = (slice(max(row - k, 0), row + k + 1), slice(max(col - k, 0), col + k + 1))
        conf = self.confidence[window].astype(np.float64)
        total = float(conf.sum())
        if total <= 0.0:
            return self.default
        return float((conf * self.value[window]).sum() / total)
