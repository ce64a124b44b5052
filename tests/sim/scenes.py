"""Tiny house meshes for navigation tests, built in milliseconds.

All rooms have a floor at y = 0, walls 0.1 m thick and 2.8 m high, and a ceiling. Every
function returns a plain :class:`Mesh` whose instance ids follow :class:`StructureId`.
"""

from __future__ import annotations

from vlln.world.mesh import Mesh, MeshBuilder
from vlln.world.model import StructureId

WALL_HEIGHT = 2.8
WALL_THICKNESS = 0.1
GREY = (0.5, 0.5, 0.5)


def _part(build: MeshBuilder, instance_id: int) -> Mesh:
    return build.build().with_instance_id(instance_id)


def floor(x0: float, z0: float, x1: float, z1: float, y: float = 0.0) -> Mesh:
    b = MeshBuilder()
    b.quad((x0, y, z0), (0.0, 0.0, z1 - z0), (x1 - x0, 0.0, 0.0), GREY, 0)
    return _part(b, StructureId.FLOOR)


def ceiling(x0: float, z0: float, x1: float, z1: float) -> Mesh:
    b = MeshBuilder()
    b.quad((x0, WALL_HEIGHT, z0), (x1 - x0, 0.0, 0.0), (0.0, 0.0, z1 - z0), GREY, 0)
    return _part(b, StructureId.CEILING)


def wall(x0: float, z0: float, x1: float, z1: float, height: float = WALL_HEIGHT) -> Mesh:
    """An axis-aligned wall along the segment (x0, z0)-(x1, z1), centred on it."""
    b = MeshBuilder()
    t = WALL_THICKNESS
    along_x = z0 == z1
    size = (abs(x1 - x0) + t, height, t) if along_x else (t, height, abs(z1 - z0) + t)
    b.box(((x0 + x1) / 2.0, height / 2.0, (z0 + z1) / 2.0), size, GREY, 0)
    return _part(b, StructureId.WALL)


def box_object(
    instance_id: int, x: float, z: float, size: tuple[float, float, float], y: float = 0.0
) -> Mesh:
    """A box standing at height ``y`` with floor-plan centre (x, z); ``size`` = (sx, sy, sz)."""
    b = MeshBuilder()
    b.box((x, y + size[1] / 2.0, z), size, GREY, 0)
    return _part(b, instance_id)


def closed_room(x0: float, z0: float, x1: float, z1: float) -> list[Mesh]:
    return [
        floor(x0, z0, x1, z1),
        ceiling(x0, z0, x1, z1),
        wall(x0, z0, x1, z0),
        wall(x0, z1, x1, z1),
        wall(x0, z0, x0, z1),
        wall(x1, z0, x1, z1),
    ]


def empty_room(width: float = 6.0, depth: float = 4.0) -> Mesh:
    """One closed rectangular room with its corner at the origin."""
    return Mesh.concatenate(closed_room(0.0, 0.0, width, depth))


def l_shaped_rooms() -> Mesh:
    """Room A (6 x 4 m) and room B (3 x 5 m, north of A's west half) joined by a 1 m door.

    The shared wall lies along z = 4 with the door gap at x in [1, 2]; the lintel above the
    door (y 2.1-2.8) must not block the passage.
    """
    parts = [
        floor(0.0, 0.0, 6.0, 4.0),
        floor(0.0, 4.0, 3.0, 9.0),
        ceiling(0.0, 0.0, 6.0, 4.0),
        ceiling(0.0, 4.0, 3.0, 9.0),
        wall(0.0, 0.0, 6.0, 0.0),
        wall(6.0, 0.0, 6.0, 4.0),
        wall(0.0, 0.0, 0.0, 9.0),
        wall(0.0, 9.0, 3.0, 9.0),
        wall(3.0, 4.0, 3.0, 9.0),
        # Shared wall with a door gap between x = 1 and x = 2.
        wall(0.0, 4.0, 0.95, 4.0),
        wall(2.05, 4.0, 6.0, 4.0),
    ]
    lintel = MeshBuilder()
    lintel.box((1.5, 2.45, 4.0), (1.0, 0.7, WALL_THICKNESS), GREY, 0)
    parts.append(_part(lintel, StructureId.DOOR_FRAME))
    return Mesh.concatenate(parts)


def divided_room() -> Mesh:
    """A 6 x 6 m room split by a wall along x = 3 from z = 0 to z = 5 (gap at the north end)."""
    return Mesh.concatenate([*closed_room(0.0, 0.0, 6.0, 6.0), wall(3.0, 0.0, 3.0, 5.0)])


def furnished_room() -> Mesh:
    """An 8 x 6 m room with furniture-like obstacles of several heights.

    * 1: a table (top at 0.75 m), 2: a tall closed wardrobe (0-2.0 m, hollow inside),
    * 3: a low rug (2 cm high, walkable), 4: a shelf hanging at 1.7-2.2 m (above the agent),
    * 5: a rotated cabinet, 6: a cylinder (a stool).
    """
    parts = closed_room(0.0, 0.0, 8.0, 6.0)
    parts.append(box_object(1, 2.0, 2.0, (1.2, 0.75, 0.8)))
    parts.append(box_object(2, 6.5, 1.0, (1.2, 2.0, 0.6)))
    parts.append(box_object(3, 4.0, 4.5, (2.0, 0.02, 1.5)))
    parts.append(box_object(4, 7.0, 5.0, (1.0, 0.5, 0.4), y=1.7))
    cabinet = MeshBuilder()
    cabinet.box((4.5, 0.45, 2.0), (0.9, 0.9, 0.5), GREY, 0, yaw=0.6)
    parts.append(_part(cabinet, 5))
    stool = MeshBuilder()
    stool.cylinder((1.5, 0.0, 4.5), 0.25, 0.45, GREY, 0, segments=16)
    parts.append(_part(stool, 6))
    return Mesh.concatenate(parts)


def two_separate_rooms() -> Mesh:
    """Two closed rooms side by side with no door between them."""
    return Mesh.concatenate([*closed_room(0.0, 0.0, 3.0, 3.0), *closed_room(4.0, 0.0, 7.0, 3.0)])
