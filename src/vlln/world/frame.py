"""The one coordinate frame used everywhere inside vlln.

We use Habitat's frame because the released VL-LN data is written in it, so no conversion is
needed for positions and rotations at the import/export boundary:

* x points right, y points up, z points toward the viewer; metres.
* A floor-plan point is ``(x, z)``; the floor of a level is at height ``y = level.floor_y``.
* Heading (``yaw``) is a rotation about +y in radians; yaw 0 looks along -z and a positive yaw
  has turned left (counter-clockwise seen from above).
* Quaternions are stored ``[x, y, z, w]`` as in the released episodes.

The only place another frame appears is the released ``region_dict.json``, whose polygons are
``[x, -z]``; :mod:`vlln.world.scene_summary` converts them.
"""

from __future__ import annotations

import math


def heading_vector(yaw: float) -> tuple[float, float]:
    """Unit floor-plan direction ``(dx, dz)`` that an agent with this yaw looks along."""
    return -math.sin(yaw), -math.cos(yaw)


def yaw_of(dx: float, dz: float) -> float:
    """Yaw that looks along the floor-plan direction ``(dx, dz)``."""
    return math.atan2(-dx, -dz)


def wrap_angle(angle: float) -> float:
    """The same angle in ``(-pi, pi]``."""
    wrapped = math.remainder(angle, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def yaw_to_quaternion(yaw: float) -> list[float]:
    """Rotation about +y as a quaternion ``[x, y, z, w]``."""
    return [0.0, math.sin(yaw / 2.0), 0.0, math.cos(yaw / 2.0)]


def quaternion_to_yaw(quaternion: list[float] | tuple[float, ...]) -> float:
    """Yaw of a quaternion ``[x, y, z, w]``; any tilt out of the floor plane is ignored."""
    x, y, z, w = (float(q) for q in quaternion)
    # Rotate the forward vector (0, 0, -1) and read its floor-plan direction.
    dx = -2.0 * (x * z + w * y)
    dz = -(1.0 - 2.0 * (x * x + y * y))
    return yaw_of(dx, dz)
