"""A straight flight of stairs in a walled shaft, joining one storey to the next.

The flight runs along one wall of a room that has the same rectangle on both storeys. Its
shaft is closed on three sides on each storey, so the flight can only be entered from its
foot on the lower storey and from its head on the upper one: a full-height side wall on the
room side, the room's own wall on the other side, a wall under the upper landing that closes
the lower storey's end, and a wall above the foot that closes the upper storey's end.
The upper storey's floor and the lower storey's ceiling have a hole above the flight.

The treads' top faces are what the navigation grid walks on (see
:mod:`vlln.sim.storeys`), so the agent's height follows the steps.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vlln.world.generator.layout import FloorPlan
from vlln.world.generator.rect import Rect
from vlln.world.materials import COLORS, material_index
from vlln.world.mesh import Mesh, MeshBuilder
from vlln.world.model import StructureId

STAIR_WIDTH = 1.2  # clear width of the flight between its walls, m
STAIR_RUN = 3.6  # length of the flight along its axis, m
STEP_COUNT = 14
LANDING = 1.0  # free floor in front of the foot and beyond the head, m
SIDE_PASSAGE = 1.0  # the room keeps at least this much floor beside the shaft, m
DOOR_CLEARANCE = 0.4  # no door opening within this distance of the shaft, m
SLAB = 0.1  # floor slab between a ceiling and the next storey's floor, m
_FACE_INSET = 0.005  # the shaft's lining stands this far in front of the room wall, m


@dataclass(frozen=True)
class StairSite:
    """Where a flight stands: the room (list index in the plan), the flight's clear footprint
    ``rect``, the axis it climbs along (``"x"`` or ``"z"``), the sign of the climb along it and
    the long side that lies against the room wall (0: the low side, ``z0`` or ``x0``)."""

    room: int
    rect: Rect
    axis: str
    sign: int
    wall_side: int

    @property
    def keep_out(self) -> Rect:
        """The flight with its landings and a margin: no furniture stands here."""
        r = self.rect
        if self.axis == "x":
            return Rect(r.x0 - LANDING, r.z0 - 0.3, r.x1 + LANDING, r.z1 + 0.3)
        return Rect(r.x0 - 0.3, r.z0 - LANDING, r.x1 + 0.3, r.z1 + LANDING)

    def along(self) -> tuple[float, float]:
        """The flight's extent along its axis: (foot, head)."""
        r = self.rect
        lo, hi = (r.x0, r.x1) if self.axis == "x" else (r.z0, r.z1)
        return (lo, hi) if self.sign > 0 else (hi, lo)

    def across(self) -> tuple[float, float]:
        """The flight's extent across its axis: (room wall side, open side)."""
        r = self.rect
        lo, hi = (r.z0, r.z1) if self.axis == "x" else (r.x0, r.x1)
        return (lo, hi) if self.wall_side == 0 else (hi, lo)

    def point(self, along: float, y: float, across: float) -> tuple[float, float, float]:
        """World ``(x, y, z)`` of a point given along and across the flight."""
        return (along, y, across) if self.axis == "x" else (across, y, along)


def storey_height(ceiling_height: float) -> float:
    """Floor-to-floor height of a storey."""
    return round(ceiling_height + SLAB, 6)


def stair_sites(plan: FloorPlan, wall_thickness: float) -> list[StairSite]:
    """Every place in the plan where a flight fits with both landings, clear of doors."""
    face = wall_thickness / 2.0
    sites: list[StairSite] = []
    for index, rect in enumerate(plan.rects):
        inner = rect.shrunk(face)
        for axis in ("x", "z"):
            length = inner.width if axis == "x" else inner.depth
            across = inner.depth if axis == "x" else inner.width
            if length < STAIR_RUN + 2.0 * LANDING or across < STAIR_WIDTH + SIDE_PASSAGE:
                continue
            lo = (inner.x0 if axis == "x" else inner.z0) + (length - STAIR_RUN) / 2.0
            for wall_side in (0, 1):
                if axis == "x":
                    z0 = inner.z0 if wall_side == 0 else inner.z1 - STAIR_WIDTH
                    flight = Rect(lo, z0, lo + STAIR_RUN, z0 + STAIR_WIDTH)
                else:
                    x0 = inner.x0 if wall_side == 0 else inner.x1 - STAIR_WIDTH
                    flight = Rect(x0, lo, x0 + STAIR_WIDTH, lo + STAIR_RUN)
                if _near_door(plan, flight.shrunk(-DOOR_CLEARANCE - face)):
                    continue
                sites += [StairSite(index, flight, axis, sign, wall_side) for sign in (1, -1)]
    return sites


def _near_door(plan: FloorPlan, zone: Rect) -> bool:
    for door in plan.doors:
        x, z = door.center
        half = door.width / 2.0
        x_lo, x_hi = (x - half, x + half) if door.axis == "x" else (x, x)
        z_lo, z_hi = (z, z) if door.axis == "x" else (z - half, z + half)
        if x_hi >= zone.x0 and x_lo <= zone.x1 and z_hi >= zone.z0 and z_lo <= zone.z1:
            return True
    return False


def overlaps(a: Rect, b: Rect) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.z0 < b.z1 and b.z0 < a.z1


def flight_mesh(site: StairSite, bottom: float, top: float, color_name: str) -> Mesh:
    """The solid steps from ``bottom`` to ``top``: a tread and a riser per step."""
    builder = MeshBuilder()
    color, material = COLORS[color_name], material_index("wood")
    foot, head = site.along()
    near, far = site.across()
    rise = (top - bottom) / STEP_COUNT
    tread = (head - foot) / STEP_COUNT  # signed
    width = site.point(0.0, 0.0, far - near)
    up = (0.0, 1.0, 0.0)
    toward_foot = site.point(-tread, 0.0, 0.0)
    for i in range(STEP_COUNT):
        a = foot + i * tread
        y = bottom + (i + 1) * rise
        tread_edge = site.point(tread, 0.0, 0.0)
        _quad(builder, site.point(a, y, near), tread_edge, width, up, color, material)
        riser = site.point(a, y - rise, near)
        _quad(builder, riser, (0.0, rise, 0.0), width, toward_foot, color, material)
    return builder.build()


def shaft_mesh(
    site: StairSite, bottom: float, top: float, ceiling_height: float, wall_thickness: float
) -> Mesh:
    """The shaft's walls (see the module docstring), all carrying ``StructureId.WALL``."""
    builder = MeshBuilder()
    color, material = COLORS["white"], material_index("plain")
    roof = top + ceiling_height
    foot, head = site.along()
    near, far = site.across()
    out = 1.0 if far > near else -1.0  # from the room wall toward the open side
    run = abs(head - foot)
    middle = (foot + head) / 2.0
    side = site.point(middle, (bottom + roof) / 2.0, far + out * wall_thickness / 2.0)
    builder.box(
        side,
        _size(site, run + 2.0 * wall_thickness, roof - bottom, wall_thickness),
        color,
        material,
    )
    # A lining in front of the room wall hides the slit where the slab meets that wall.
    _quad(
        builder,
        site.point(min(foot, head), bottom, near + out * _FACE_INSET),
        site.point(run, 0.0, 0.0),
        (0.0, roof - bottom, 0.0),
        site.point(0.0, 0.0, out),
        color,
        material,
    )
    step = 1.0 if head > foot else -1.0
    width = abs(far - near)
    # The wall above the foot starts at the lower ceiling, closing the slab between storeys.
    above_foot = bottom + ceiling_height
    for end, sign, lo_y, hi_y in ((head, step, bottom, top), (foot, -step, above_foot, roof)):
        centre = site.point(
            end + sign * wall_thickness / 2.0, (lo_y + hi_y) / 2.0, (near + far) / 2.0
        )
        builder.box(centre, _size(site, wall_thickness, hi_y - lo_y, width), color, material)
    return builder.build().with_instance_id(StructureId.WALL)


Vec3 = tuple[float, float, float]


def _size(site: StairSite, along: float, height: float, across: float) -> Vec3:
    return (along, height, across) if site.axis == "x" else (across, height, along)


def _quad(
    builder: MeshBuilder, corner: Vec3, u: Vec3, v: Vec3, facing: Vec3, color: Vec3, material: int
) -> None:
    """The parallelogram ``corner + a u + b v``, turned to face along ``facing``."""
    if float(np.dot(np.cross(u, v), facing)) < 0.0:
        u, v = v, u
    builder.quad(corner, u, v, color, material)


def without_area(mesh: Mesh, structure: StructureId, rect: Rect, hole: Rect) -> Mesh:
    """``mesh`` with its ``structure`` quads inside ``rect`` replaced by ``rect`` minus ``hole``
    (same colour, material and height); used to open a floor and a ceiling above a flight."""
    triangles = mesh.positions.reshape(-1, 3, 3)
    ids = mesh.instance_ids[::3]
    centre = triangles.mean(axis=1)
    inside = (
        (ids == structure)
        & (centre[:, 0] > rect.x0)
        & (centre[:, 0] < rect.x1)
        & (centre[:, 2] > rect.z0)
        & (centre[:, 2] < rect.z1)
    )
    if not inside.any():
        return mesh
    first = int(np.flatnonzero(inside)[0]) * 3
    y = float(mesh.positions[first, 1])
    facing_up = float(mesh.normals[first, 1]) > 0.0
    color = tuple(float(c) for c in mesh.colors[first])
    material = int(mesh.materials[first])
    keep = np.repeat(~inside, 3)
    kept = Mesh(
        mesh.positions[keep],
        mesh.normals[keep],
        mesh.uvs[keep],
        mesh.colors[keep],
        mesh.materials[keep],
        mesh.instance_ids[keep],
    )
    builder = MeshBuilder()
    for piece in _minus(rect, hole):
        u, v = (0.0, 0.0, piece.depth), (piece.width, 0.0, 0.0)
        if not facing_up:
            u, v = v, u
        builder.quad((piece.x0, y, piece.z0), u, v, (color[0], color[1], color[2]), material)
    return Mesh.concatenate([kept, builder.build().with_instance_id(structure)])


def _minus(rect: Rect, hole: Rect) -> list[Rect]:
    """``rect`` minus ``hole`` (inside it) as up to four rectangles."""
    pieces = [
        Rect(rect.x0, rect.z0, rect.x1, hole.z0),
        Rect(rect.x0, hole.z1, rect.x1, rect.z1),
        Rect(rect.x0, hole.z0, hole.x0, hole.z1),
        Rect(hole.x1, hole.z0, rect.x1, hole.z1),
    ]
    return [p for p in pieces if p.width > 1e-9 and p.depth > 1e-9]
