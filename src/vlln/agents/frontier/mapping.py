"""The agent's own top-down map, built from depth alone, in the start frame of its GPS.

Each frame is back-projected (a subsample of pixels, with the camera intrinsics and tilt) into
the frame that the ``gps``/``compass`` observations use: the start position is the origin and
the start heading looks along -z. Points in a height band above the floor are obstacles; floor
points and the free space along each image column up to its first obstacle are explored free
space. The map is a fixed square of cells around the start, big enough for any house; every
operation that scales with area works on the explored bounding box only.

Obstacles, once seen, stay (the world is static and the depth is exact), so a ray that grazes a
corner cannot erase a wall. Low obstacles hidden below the camera's field of view near the
agent are found by bumping into them (:meth:`ObstacleMap.mark_blocked_ahead`).

In a house with several storeys each storey has its own map, and heights are measured from
that storey's floor (the agent's feet may stand above it, on stairs). Points well below the
floor belong to a storey below and are left out. Pixels the detector calls stairs are neither
floor nor obstacle: their cells form the stairs layer, walkable, with the highest and lowest
stair point seen in each cell, which tells where the flight leads (see ``stairs.py``).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple, Self, TypeVar

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator

from vlln.config import Count, settings_dataclass
from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec
from vlln.world.frame import heading_vector

_Pixel = TypeVar("_Pixel", bound=np.generic)


class Pose(NamedTuple):
    """The agent in the start frame: floor-plan position (x, z) and yaw (see world.frame)."""

    x: float
    z: float
    yaw: float


class CellBox(NamedTuple):
    """Rows ``r0:r1`` and columns ``c0:c1`` of the map (half-open)."""

    r0: int
    r1: int
    c0: int
    c1: int


@settings_dataclass
class MapConfig:
    """Resolution and sensing limits of the map."""

    cell_size: float = Field(default=0.1, ge=0.01, le=0.5)
    extent: float = 60.0  # side of the square map, metres, centred on the start
    pixel_stride: Count = 4  # back-project every n-th pixel in both directions
    floor_height: float = 0.08  # points lower than this are floor
    below_floor: float = 0.3  # ... unless this far below it: they are on a storey below
    stair_step: float = 0.3  # stair cells further than this from the floor are off it (steep)
    obstacle_band: tuple[float, float] = (0.15, 1.5)  # points in this band are obstacles
    free_range: float = 5.0  # free space is traced this far along each column at most
    obstacle_range: float = 7.0  # obstacle points farther than this are ignored

    @model_validator(mode="after")
    def _consistent(self) -> Self:
        if not self.extent > 4.0 * self.free_range:
            raise ConfigError(
                f"extent ({self.extent} m) must exceed 4 * free_range ({self.free_range} m)"
            )
        low, high = self.obstacle_band
        if not -self.below_floor < self.floor_height < low < high:
            raise ConfigError(
                f"need -below_floor < floor_height < obstacle_band[0] < obstacle_band[1], got "
                f"{self.below_floor}, {self.floor_height}, {self.obstacle_band}"
            )
        return self


class ObstacleMap:
    """Obstacle and explored cells; rows run along +z, columns along +x."""

    def __init__(self, camera: CameraSpec, config: MapConfig | None = None) -> None:
        self.config = config or MapConfig()
        self.camera = camera
        cfg = self.config
        self.cell_size = cfg.cell_size
        n = math.ceil(cfg.extent / cfg.cell_size)
        self.shape = (n, n)
        self.origin = (-n * cfg.cell_size / 2.0, -n * cfg.cell_size / 2.0)
        self.obstacle = np.zeros(self.shape, bool)
        self.explored = np.zeros(self.shape, bool)
        self.stairs = np.zeros(self.shape, bool)
        self.stair_high = np.full(self.shape, -np.inf, np.float32)  # highest stair point
        self.stair_low = np.full(self.shape, np.inf, np.float32)  # lowest stair point
        self._box = CellBox(n // 2, n // 2 + 1, n // 2, n // 2 + 1)
        stride = cfg.pixel_stride
        us = np.arange(stride // 2, camera.width, stride)
        vs = np.arange(stride // 2, camera.height, stride)
        self._pixels = (slice(stride // 2, None, stride), slice(stride // 2, None, stride))
        uu, vv = np.meshgrid(us, vs)
        rays = camera.pixel_ray(uu, vv)  # (h, w, 3), unit z-depth
        self._ray_x = rays[..., 0].astype(np.float32)
        self._ray_y = rays[..., 1].astype(np.float32)
        # Horizontal direction of each column in the camera frame (level camera).
        column_x = rays[0, :, 0]
        norm = np.hypot(column_x, 1.0)
        self._column_dirs = np.stack([column_x / norm, -1.0 / norm], axis=1)  # (w, 2): x, z
        self._trace_steps = np.arange(0.0, cfg.free_range, cfg.cell_size * 0.7)
        self._offsets: dict[float, tuple[NDArray[np.intp], NDArray[np.intp]]] = {}

    # ----------------------------------------------------------------- images
    def subsample(self, image: NDArray[_Pixel]) -> NDArray[_Pixel]:
        """The pixels of a full-size image that the map back-projects."""
        return image[self._pixels]

    @property
    def pixel_area(self) -> int:
        """Full-resolution pixels that one back-projected pixel stands for."""
        return self.config.pixel_stride**2

    # ----------------------------------------------------------------- cells
    def cell_of(self, x: float, z: float) -> tuple[int, int]:
        s = self.cell_size
        return math.floor((z - self.origin[1]) / s), math.floor((x - self.origin[0]) / s)

    def cell_centre(self, row: float, col: float) -> tuple[float, float]:
        s = self.cell_size
        return self.origin[0] + (col + 0.5) * s, self.origin[1] + (row + 0.5) * s

    def flat_cells(self, x: NDArray[np.floating], z: NDArray[np.floating]) -> NDArray[np.intp]:
        """Flat indices of the cells holding the points; points off the map are dropped."""
        s = self.cell_size
        cols = np.floor((x - self.origin[0]) / s).astype(np.intp)
        rows = np.floor((z - self.origin[1]) / s).astype(np.intp)
        n_rows, n_cols = self.shape
        inside = (rows >= 0) & (rows < n_rows) & (cols >= 0) & (cols < n_cols)
        flat: NDArray[np.intp] = rows[inside] * n_cols + cols[inside]
        return flat

    def box(self, margin: int = 0) -> CellBox:
        """Bounding box of everything explored so far, grown by ``margin`` cells."""
        r0, r1, c0, c1 = self._box
        n_rows, n_cols = self.shape
        return CellBox(
            max(0, r0 - margin),
            min(n_rows, r1 + margin),
            max(0, c0 - margin),
            min(n_cols, c1 + margin),
        )

    # ----------------------------------------------------------------- updates
    def mark_free_disc(self, pose: Pose, radius: float) -> None:
        """Explore a disc around the agent: where it stands is floor."""
        r, c = self.cell_of(pose.x, pose.z)
        k = math.ceil(radius / self.cell_size)
        rows, cols = np.mgrid[r - k : r + k + 1, c - k : c + k + 1]
        inside = (rows - r) ** 2 + (cols - c) ** 2 <= (radius / self.cell_size) ** 2
        flat = self._clip_flat(rows[inside], cols[inside])
        self.explored.flat[flat] = True
        self._grow_box(flat)

    def mark_blocked_ahead(self, pose: Pose, distance: float, half_width: float) -> None:
        """A forward move made no progress: something too low to see is in front."""
        hx, hz = heading_vector(pose.yaw)
        along = np.arange(distance, distance + 2.0 * self.cell_size, self.cell_size / 2.0)
        across = np.arange(-half_width, half_width + 1e-9, self.cell_size / 2.0)
        a, b = np.meshgrid(along, across)
        x = pose.x + a * hx - b * hz
        z = pose.z + a * hz + b * hx
        flat = self.flat_cells(x.ravel(), z.ravel())
        self.obstacle.flat[flat] = True
        self.explored.flat[flat] = True
        self._grow_box(flat)

    def mark_stairs(
        self, x: NDArray[np.floating], z: NDArray[np.floating], y: NDArray[np.floating]
    ) -> NDArray[np.intp]:
        """Stair points at heights ``y`` above the floor: their cells are explored stairs.
        Returns the cells that became steep (see :meth:`steep`)."""
        all_cells = self._flat_or_minus_one(np.asarray(x), np.asarray(z))
        inside = all_cells >= 0
        flat, heights = np.unique(all_cells[inside]), np.asarray(y, np.float32)[inside]
        was_steep = self.steep(flat)
        self.stairs.flat[flat] = True
        self.explored.flat[flat] = True
        np.maximum.at(self.stair_high.reshape(-1), all_cells[inside], heights)
        np.minimum.at(self.stair_low.reshape(-1), all_cells[inside], heights)
        self._grow_box(flat)
        return flat[self.steep(flat) & ~was_steep]

    def steep(self, cells: NDArray[np.intp]) -> NDArray[np.bool_]:
        """Which of the cells (flat indices) are stairs too far above or below the floor to
        step onto from it."""
        return self._steep_at(np.unravel_index(cells, self.shape))

    def steep_window(self, box: CellBox) -> NDArray[np.bool_]:
        """:meth:`steep` for every cell of a window."""
        return self._steep_at((slice(box.r0, box.r1), slice(box.c0, box.c1)))

    def _steep_at(self, index: Any) -> NDArray[np.bool_]:
        step = self.config.stair_step
        high, low = self.stair_high[index], self.stair_low[index]
        steep: NDArray[np.bool_] = self.stairs[index] & ((high > step) | (low < -step))
        return steep

    def update(
        self,
        depth: NDArray[np.float32],
        pose: Pose,
        tilt: float,
        feet: float = 0.0,
        walkable: NDArray[np.bool_] | None = None,
    ) -> NDArray[np.intp]:
        """Add one depth frame; returns the flat indices of cells that became obstacles (or
        steep stairs, which paths avoid as well).

        ``feet``: the agent's height above this storey's floor; ``walkable``: the
        back-projected pixels (:meth:`subsample`) that the detector calls stairs."""
        cfg = self.config
        d, valid, (x, y, z), squared = self._points(depth, pose, tilt, feet)
        low, high = cfg.obstacle_band
        is_obstacle = valid & (y > low) & (y < high) & (squared < cfg.obstacle_range**2)
        is_floor = valid & (y < cfg.floor_height) & (y > -cfg.below_floor)
        if walkable is not None and walkable.any():
            stairs = valid & walkable & (squared < cfg.obstacle_range**2)
            is_obstacle &= ~walkable
            is_floor &= ~walkable
            steep = self.mark_stairs(x[stairs], z[stairs], y[stairs])
        flat = self._flat_or_minus_one(x, z)
        obstacle_cells = flat[is_obstacle]
        obstacle_cells = obstacle_cells[obstacle_cells >= 0]
        new = np.unique(obstacle_cells[~self.obstacle.flat[obstacle_cells]])
        self.obstacle.flat[obstacle_cells] = True
        seen = flat[is_obstacle | is_floor]
        seen = seen[seen >= 0]
        self.explored.flat[seen] = True
        self._grow_box(seen)
        if tilt == 0.0:
            # A hole in the floor (the way down a flight) stops free space like an obstacle.
            is_drop = valid & (y < -cfg.below_floor)
            self._trace_free(pose, squared, is_obstacle | is_drop, is_floor, valid, d)
        if walkable is not None and walkable.any():
            new = np.union1d(new, steep)
        return new

    def update_stairs(
        self,
        depth: NDArray[np.float32],
        pose: Pose,
        tilt: float,
        feet: float,
        walkable: NDArray[np.bool_],
    ) -> None:
        """Add only the stairs of a frame (a look down a flight from its head)."""
        _, valid, (x, y, z), squared = self._points(depth, pose, tilt, feet)
        stairs = valid & walkable & (squared < self.config.obstacle_range**2)
        self.mark_stairs(x[stairs], z[stairs], y[stairs])

    def _points(
        self, depth: NDArray[np.float32], pose: Pose, tilt: float, feet: float
    ) -> tuple[
        NDArray[np.float32],
        NDArray[np.bool_],
        tuple[NDArray[np.float32], NDArray[np.float32], NDArray[np.float32]],
        NDArray[np.float32],
    ]:
        """Depth, validity, (x, y, z) and squared floor-plan distance from the agent of the
        back-projected pixels; y is the height above the floor."""
        d = np.asarray(depth, np.float32)[self._pixels]
        valid = (d > 0.0) & (d < self.camera.max_depth * 0.999)
        pose_matrix = self.camera.camera_to_world((pose.x, 0.0, pose.z), pose.yaw, tilt)
        r = pose_matrix[:3, :3].astype(np.float32)
        # Camera-frame point = ray * depth with ray = (rx, ry, -1); rotate and translate.
        cx, cy = self._ray_x * d, self._ray_y * d
        x = r[0, 0] * cx + r[0, 1] * cy - r[0, 2] * d + np.float32(pose.x)
        y = r[1, 0] * cx + r[1, 1] * cy - r[1, 2] * d + np.float32(pose_matrix[1, 3] + feet)
        z = r[2, 0] * cx + r[2, 1] * cy - r[2, 2] * d + np.float32(pose.z)
        dx, dz = x - np.float32(pose.x), z - np.float32(pose.z)
        return d, valid, (x, y, z), dx * dx + dz * dz

    def _flat_or_minus_one(
        self, x: NDArray[np.floating], z: NDArray[np.floating]
    ) -> NDArray[np.intp]:
        """Flat cell index of every point, -1 for points off the map."""
        s = self.cell_size
        cols = np.floor((x - self.origin[0]) / s).astype(np.intp)
        rows = np.floor((z - self.origin[1]) / s).astype(np.intp)
        n_rows, n_cols = self.shape
        inside = (rows >= 0) & (rows < n_rows) & (cols >= 0) & (cols < n_cols)
        flat: NDArray[np.intp] = np.where(inside, rows * n_cols + cols, -1)
        return flat

    def _trace_free(
        self,
        pose: Pose,
        squared: NDArray[np.float32],
        is_obstacle: NDArray[np.bool_],
        is_floor: NDArray[np.bool_],
        valid: NDArray[np.bool_],
        depth: NDArray[np.float32],
    ) -> None:
        """Explore each level column from the camera to its first obstacle or drop (or as far
        as it sees floor, or ``free_range`` where nothing was hit).

        The cells along each column's ray are fixed offsets from the agent's cell for a given
        heading, so they are computed once per heading (the agent only ever faces a few)."""
        cfg = self.config
        nearest_obstacle = np.sqrt(np.where(is_obstacle, squared, np.inf).min(axis=0))
        farthest_floor = np.sqrt(np.where(is_floor, squared, 0.0).max(axis=0))
        open_column = (~valid & (depth > 0.0)).any(axis=0)
        reach = np.where(open_column, cfg.free_range, farthest_floor)
        reach = np.minimum(np.minimum(nearest_obstacle, reach), cfg.free_range) - self.cell_size
        offsets = self._ray_offsets(pose.yaw)
        row, col = self.cell_of(pose.x, pose.z)
        keep = self._trace_steps[None, :] < reach[:, None]
        rows = row + offsets[0][keep]
        cols = col + offsets[1][keep]
        flat = self._clip_flat(rows, cols)
        self.explored.flat[flat] = True
        self._grow_box(flat)

    def _ray_offsets(self, yaw: float) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
        """(row, col) offsets of the cells along every column's ray, per trace step."""
        key = round(yaw, 6)
        cached = self._offsets.get(key)
        if cached is None:
            c, s = math.cos(yaw), math.sin(yaw)
            dirs = self._column_dirs
            # Rotate the camera-frame (x, z) directions about +y by the yaw.
            wx = c * dirs[:, 0] + s * dirs[:, 1]
            wz = -s * dirs[:, 0] + c * dirs[:, 1]
            steps = self._trace_steps[None, :] / self.cell_size
            cached = (
                np.rint(wz[:, None] * steps).astype(np.intp),
                np.rint(wx[:, None] * steps).astype(np.intp),
            )
            self._offsets[key] = cached
        return cached

    # ----------------------------------------------------------------- internals
    def _clip_flat(self, rows: NDArray[np.intp], cols: NDArray[np.intp]) -> NDArray[np.intp]:
        n_rows, n_cols = self.shape
        inside = (rows >= 0) & (rows < n_rows) & (cols >= 0) & (cols < n_cols)
        flat: NDArray[np.intp] = rows[inside] * n_cols + cols[inside]
        return flat

    def _grow_box(self, flat: NDArray[np.intp]) -> None:
        if flat.size == 0:
            return
        n_cols = self.shape[1]
        rows, cols = flat // n_cols, flat % n_cols
        r0, r1, c0, c1 = self._box
        self._box = CellBox(
            min(r0, int(rows.min())),
            max(r1, int(rows.max()) + 1),
            min(c0, int(cols.min())),
            max(c1, int(cols.max()) + 1),
        )
