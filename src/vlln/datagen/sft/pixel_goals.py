"""Where a later position of the agent shows on an earlier look-down image.

A pixel goal is the floor point under the agent's feet at a later frame, projected into the
look-down (30° down) image of the frame where the decision is made. It is only a valid goal
if the point lies in front of the camera, inside the image, and is what the image shows there:
the rendered z-depth at the pixel must match the projected z-depth within a tolerance, so a
point hidden behind furniture or a wall is never a target. The pose is the one recorded in the
dataset (eye position and rotation quaternion of the down camera), the intrinsics those of
:class:`CameraSpec`; back-projecting the pixel with its depth lands on the same point.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.spatial.transform import Rotation

from vlln.errors import DataFormatError
from vlln.sim.camera import CameraSpec

Pixel = tuple[int, int]

# Rounding to the nearest pixel centre sends halves up; a point straight ahead projects onto
# column (width - 1) / 2 + float noise, and this margin keeps the noise from deciding.
_HALF_UP_MARGIN = 1e-6


def project_point(
    spec: CameraSpec, eye: NDArray[Any], rotation: NDArray[Any], point: NDArray[Any]
) -> tuple[float, float, float]:
    """``(u, v, z_depth)`` of a world point for a camera at ``eye`` with rotation quaternion
    ``[x, y, z, w]`` (camera looks along its -z); depth <= 0 means behind the camera."""
    to_world = Rotation.from_quat(np.asarray(rotation, np.float64)).as_matrix()
    local = to_world.T @ (np.asarray(point, np.float64) - np.asarray(eye, np.float64))
    depth = -float(local[2])
    if depth <= 0.0:
        return math.nan, math.nan, depth
    fx, fy, cx, cy = spec.intrinsics()
    return cx + fx * float(local[0]) / depth, cy - fy * float(local[1]) / depth, depth


def visible_pixel(
    spec: CameraSpec,
    eye: NDArray[Any],
    rotation: NDArray[Any],
    depth_image: NDArray[np.float32],
    point: NDArray[Any],
    tolerance: float,
) -> Pixel | None:
    """The pixel showing ``point``, or None if it is behind the camera, outside the image, or
    hidden (rendered depth differs by more than ``tolerance``). The pixel is the nearest
    pixel centre, halves rounded up (column ``floor(u + 0.5)``, row ``floor(v + 0.5)``)."""
    u, v, depth = project_point(spec, eye, rotation, point)
    if depth <= spec.near:
        return None
    column = math.floor(u + 0.5 + _HALF_UP_MARGIN)
    row = math.floor(v + 0.5 + _HALF_UP_MARGIN)
    if not (0 <= column < spec.width and 0 <= row < spec.height):
        return None
    if abs(float(depth_image[row, column]) - depth) > tolerance:
        return None
    return column, row


class GoalLocator:
    """Answers "which pixel of frame t's look-down image shows the feet at frame s?" for one
    trajectory; depth images are read on demand, the latest one kept."""

    def __init__(
        self,
        spec: CameraSpec,
        feet: NDArray[np.float64],
        eyes: NDArray[np.float64],
        rotations: NDArray[np.float64],
        read_depth: Callable[[int], NDArray[np.float32]],
        tolerance: float,
    ) -> None:
        self.spec = spec
        self.feet = feet
        self.eyes = eyes
        self.rotations = rotations
        self.read_depth = read_depth
        self.tolerance = tolerance
        self._depth: tuple[int, NDArray[np.float32]] | None = None

    def __call__(self, frame: int, later: int) -> Pixel | None:
        if self._depth is None or self._depth[0] != frame:
            self._depth = (frame, self.read_depth(frame))
        depth = self._depth[1]
        if depth.shape != (self.spec.height, self.spec.width):
            raise DataFormatError(
                f"look-down depth of frame {frame} is {depth.shape[1]}x{depth.shape[0]}, the "
                f"camera info says {self.spec.width}x{self.spec.height}"
            )
        return visible_pixel(
            self.spec,
            self.eyes[frame],
            self.rotations[frame],
            depth,
            self.feet[later],
            self.tolerance,
        )
