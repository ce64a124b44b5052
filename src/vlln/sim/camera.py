"""The agent's pinhole camera: intrinsics, pose matrices and back-projection.

One :class:`CameraSpec` describes the sensor (size, field of view, mounting height, depth
range); the pose comes per frame as the agent's feet position, its yaw (see
:mod:`vlln.world.frame`) and the camera tilt. The same numbers drive the OpenGL matrices of the
renderer and the back-projection of a pixel with its depth, so a pixel goal chosen on an image
lands exactly on the surface that was drawn there.

Image convention: pixel ``(u, v)`` is column ``u`` (to the right) and row ``v`` (down, row 0 is
the top of the image); pixel centres sit at integer coordinates, hence ``cx = (width - 1) / 2``.
Depth is the z-distance along the optical axis, not the distance along the ray.
"""

from __future__ import annotations

import math
from typing import Annotated, NamedTuple, Self

import numpy as np
from numpy.typing import ArrayLike, NDArray
from pydantic import Field, model_validator

from vlln.config import settings_dataclass
from vlln.errors import ConfigError

Matrix4 = NDArray[np.float64]
Position = tuple[float, float, float] | NDArray[np.floating]
Pixels = Annotated[int, Field(ge=1, le=8192, strict=True)]


class Intrinsics(NamedTuple):
    """Pinhole intrinsics in pixels."""

    fx: float
    fy: float
    cx: float
    cy: float


@settings_dataclass
class CameraSpec:
    """The RGB-D sensor of the agent; defaults follow the reference benchmark."""

    width: Pixels = 640
    height: Pixels = 480
    hfov_deg: float = Field(default=79.0, ge=1.0, le=170.0)
    height_m: float = Field(default=1.25, ge=0.0, le=10.0)  # optical centre above the feet
    near: float = Field(default=0.05, ge=1e-4, le=10.0)
    far: float = Field(default=50.0, le=1e5)
    max_depth: float = Field(default=10.0, gt=0.0)  # depth values beyond this are clamped to it

    @model_validator(mode="after")
    def _depth_range(self) -> Self:
        if not self.near < self.far:
            raise ConfigError(f"far = {self.far} must be greater than near ({self.near})")
        if not self.max_depth <= self.far:
            raise ConfigError(f"max_depth = {self.max_depth} must be at most far ({self.far})")
        return self

    def intrinsics(self) -> Intrinsics:
        """``fx, fy, cx, cy``; square pixels, so ``fy = fx``."""
        focal = (self.width / 2.0) / math.tan(math.radians(self.hfov_deg) / 2.0)
        return Intrinsics(focal, focal, (self.width - 1) / 2.0, (self.height - 1) / 2.0)

    @property
    def vfov_deg(self) -> float:
        """Vertical field of view implied by the horizontal one and the aspect ratio."""
        fy = self.intrinsics().fy
        return math.degrees(2.0 * math.atan((self.height / 2.0) / fy))

    def projection_matrix(self) -> Matrix4:
        """OpenGL projection (camera looks along -z) with the image rows flipped.

        Flipping y here makes row 0 of the read-back framebuffer the top of the image, so no
        numpy flip is needed; it also reverses the winding of every projected triangle, which
        the renderer accounts for when culling.
        """
        fx, fy, _, _ = self.intrinsics()
        n, f = self.near, self.far
        matrix = np.zeros((4, 4))
        matrix[0, 0] = fx / (self.width / 2.0)
        matrix[1, 1] = -fy / (self.height / 2.0)
        matrix[2, 2] = -(f + n) / (f - n)
        matrix[2, 3] = -2.0 * f * n / (f - n)
        matrix[3, 2] = -1.0
        return matrix

    def eye(self, position: Position) -> NDArray[np.float64]:
        """World position of the optical centre for an agent whose feet are at ``position``."""
        return np.asarray(position, np.float64).reshape(3) + np.array([0.0, self.height_m, 0.0])

    def camera_to_world(self, position: Position, yaw: float, tilt: float) -> Matrix4:
        """Pose of the camera: columns are its right, up and backward axes, then the eye.

        ``tilt`` pitches the camera about its right axis; negative looks down.
        """
        cy, sy = math.cos(yaw), math.sin(yaw)
        ct, st = math.cos(tilt), math.sin(tilt)
        turn = np.array([[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]])
        pitch = np.array([[1.0, 0.0, 0.0], [0.0, ct, -st], [0.0, st, ct]])
        pose = np.eye(4)
        pose[:3, :3] = turn @ pitch
        pose[:3, 3] = self.eye(position)
        return pose

    def view_matrix(self, position: Position, yaw: float, tilt: float = 0.0) -> Matrix4:
        """World-to-camera transform (OpenGL convention: camera looks along -z, y up)."""
        pose = self.camera_to_world(position, yaw, tilt)
        rotation_t = pose[:3, :3].T
        view = np.eye(4)
        view[:3, :3] = rotation_t
        view[:3, 3] = -rotation_t @ pose[:3, 3]
        return view

    def pixel_ray(self, u: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
        """Camera-frame direction through pixel ``(u, v)``, scaled to unit z-depth.

        Multiplying by a depth value gives the camera-frame point; shape ``(..., 3)``.
        """
        fx, fy, cx, cy = self.intrinsics()
        u_arr, v_arr = np.broadcast_arrays(np.asarray(u, np.float64), np.asarray(v, np.float64))
        x = (u_arr - cx) / fx
        y = -(v_arr - cy) / fy
        return np.stack([x, y, -np.ones_like(x)], axis=-1)

    def unproject(
        self,
        u: ArrayLike,
        v: ArrayLike,
        depth: ArrayLike,
        position: Position,
        yaw: float,
        tilt: float = 0.0,
    ) -> NDArray[np.float64]:
        """World point seen at pixel ``(u, v)`` with z-depth ``depth``; shape ``(..., 3)``."""
        rays = self.pixel_ray(u, v) * np.asarray(depth, np.float64)[..., None]
        pose = self.camera_to_world(position, yaw, tilt)
        result: NDArray[np.float64] = rays @ pose[:3, :3].T + pose[:3, 3]
        return result

    def sphere_visibility(
        self,
        centres: NDArray[np.floating],
        radii: NDArray[np.floating],
        position: Position,
        yaw: float,
        tilt: float = 0.0,
    ) -> tuple[NDArray[np.bool_], NDArray[np.float64]]:
        """Which spheres may show in the image (a conservative frustum test), and the z-depth
        of their centres; ``centres`` is ``(n, 3)``, ``radii`` is ``(n,)``."""
        view = self.view_matrix(position, yaw, tilt)
        camera_points = np.asarray(centres, np.float64) @ view[:3, :3].T + view[:3, 3]
        depth = -camera_points[:, 2]
        r = np.asarray(radii, np.float64)
        fx, fy, _, _ = self.intrinsics()
        tan_x, tan_y = (self.width / 2.0) / fx, (self.height / 2.0) / fy
        # Signed distance to a side plane through the eye, e.g. x = tan_x * depth.
        beyond_x = np.abs(camera_points[:, 0]) - tan_x * depth
        beyond_y = np.abs(camera_points[:, 1]) - tan_y * depth
        visible = (
            (depth + r > self.near)
            & (depth - r < self.far)
            & (beyond_x <= r * math.sqrt(1.0 + tan_x * tan_x))
            & (beyond_y <= r * math.sqrt(1.0 + tan_y * tan_y))
        )
        return visible, depth
