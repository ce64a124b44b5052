"""Part shapes that MeshBuilder's axis-aligned primitives cannot make directly.

Tilted boards (a laptop lid, a lamp arm, a bicycle tube) and rings (a mug handle, a wheel, a
clock rim) recur across the catalogue; building them here keeps the category modules about
what an object looks like rather than about vector algebra.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import NDArray

from vlln.world.materials import Rgb
from vlln.world.mesh import Mesh, MeshBuilder, Vec3

_AXES: dict[str, tuple[Vec3, Vec3, Vec3]] = {  # ring plane (u, v) and its axis n
    "x": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)),
    "y": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "z": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
}


def shade(color: Rgb, factor: float) -> Rgb:
    """The colour made darker (factor < 1) or lighter (factor > 1), clipped to [0, 1]."""
    r, g, b = (min(1.0, max(0.0, c * factor)) for c in color)
    return (r, g, b)


def facing_quad(
    b: MeshBuilder,
    corner: NDArray[np.float64],
    edge_u: NDArray[np.float64],
    edge_v: NDArray[np.float64],
    outward: NDArray[np.float64],
    color: Rgb,
    material: int,
) -> None:
    """A parallelogram whose normal points along ``outward`` whatever the edge order."""
    normal = _cross(edge_u, edge_v)
    if float(np.dot(normal, outward)) < 0.0:
        edge_u, edge_v, normal = edge_v, edge_u, -normal
    length = math.sqrt(float(np.dot(normal, normal)))
    if length == 0.0:
        return
    lu, lv = math.sqrt(float(np.dot(edge_u, edge_u))), math.sqrt(float(np.dot(edge_v, edge_v)))
    corners = np.array([corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v])
    tex = np.array([(0.0, 0.0), (lu, 0.0), (lu, lv), (0.0, lv)])
    order = [0, 1, 2, 0, 2, 3]
    b.add_triangles(corners[order], np.tile(normal / length, (6, 1)), tex[order], color, material)


def facing_polygon(
    b: MeshBuilder,
    corners: list[NDArray[np.float64]],
    outward: NDArray[np.float64],
    color: Rgb,
    material: int,
) -> None:
    """A flat convex quadrilateral (e.g. a trapezoid) facing ``outward``, as two triangles."""
    p = np.array(corners, np.float64)
    normal = _cross(p[1] - p[0], p[2] - p[0])
    if float(np.dot(normal, outward)) < 0.0:
        p = p[::-1]
        normal = -normal
    normal /= float(np.linalg.norm(normal))
    tangent = (p[1] - p[0]) / float(np.linalg.norm(p[1] - p[0]))
    bitangent = np.cross(normal, tangent)
    uv = np.stack([(p - p[0]) @ tangent, (p - p[0]) @ bitangent], axis=1)
    order = [0, 1, 2, 0, 2, 3]
    b.add_triangles(p[order], np.tile(normal, (6, 1)), uv[order], color, material)


def beam(
    b: MeshBuilder,
    start: Vec3,
    end: Vec3,
    width: float,
    thickness: float,
    color: Rgb,
    material: int,
    side: Vec3 = (1.0, 0.0, 0.0),
) -> None:
    """A box running from ``start`` to ``end`` (centres of its end faces).

    ``width`` lies along ``side`` (made perpendicular to the run) and ``thickness`` across
    both, so a tilted board needs no rotation matrix.
    """
    p0 = np.asarray(start, np.float64)
    run = np.asarray(end, np.float64) - p0
    length = float(np.linalg.norm(run))
    if length == 0.0:
        raise ValueError("a beam needs distinct start and end points")
    along = run / length
    across = np.asarray(side, np.float64)
    across = across - float(np.dot(across, along)) * along
    if float(np.linalg.norm(across)) < 1e-9:  # side parallel to the run: pick any normal
        across = np.cross(along, (0.0, 0.0, 1.0) if abs(along[2]) < 0.9 else (1.0, 0.0, 0.0))
    across /= float(np.linalg.norm(across))
    depth = np.cross(across, along)
    ew, et = across * width, depth * thickness
    origin = p0 - ew / 2.0 - et / 2.0
    for corner, u, v, out in (
        (origin, run, et, -ew),
        (origin + ew, run, et, ew),
        (origin, ew, et, -along),
        (origin + run, ew, et, along),
        (origin, ew, run, -depth),
        (origin + et, ew, run, depth),
    ):
        facing_quad(b, corner, u, v, out, color, material)


def ring(
    b: MeshBuilder,
    center: Vec3,
    radius: float,
    tube: float,
    depth: float,
    color: Rgb,
    material: int,
    axis: str = "z",
    segments: int = 12,
    arc: tuple[float, float] = (0.0, 2.0 * math.pi),
) -> None:
    """A flat ring (or an arc of one) of square-ish section around ``axis`` through ``center``.

    ``radius`` is the outer radius, ``tube`` the radial thickness and ``depth`` the extent
    along the axis; ``arc`` angles start at the plane's first direction (+x for the z and y
    axes, +z for the x axis) and turn towards its second.
    """
    if axis not in _AXES:
        raise ValueError(f"axis must be 'x', 'y' or 'z', not {axis!r}")
    u, v, n = (np.asarray(e, np.float64) for e in _AXES[axis])
    c = np.asarray(center, np.float64) - n * depth / 2.0
    inner = radius - tube
    angles = np.linspace(arc[0], arc[1], segments + 1)
    for a0, a1 in itertools.pairwise(angles):
        d0 = math.cos(a0) * u + math.sin(a0) * v
        d1 = math.cos(a1) * u + math.sin(a1) * v
        mid = (d0 + d1) / 2.0
        along = n * depth
        facing_quad(b, c + d0 * radius, (d1 - d0) * radius, along, mid, color, material)
        facing_quad(b, c + d0 * inner, (d1 - d0) * inner, along, -mid, color, material)
        for base, out in ((c, -n), (c + along, n)):
            corners = [base + d0 * inner, base + d0 * radius, base + d1 * radius, base + d1 * inner]
            facing_polygon(b, corners, out, color, material)


def rotated_about_x(mesh: Mesh, angle: float) -> Mesh:
    """The mesh turned by ``angle`` about +x (positive tips +y towards -z), set on the floor."""
    c, s = math.cos(angle), math.sin(angle)
    rotation = np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]], np.float32)
    positions = mesh.positions @ rotation.T
    normals = mesh.normals @ rotation.T
    turned = Mesh(positions, normals, mesh.uvs, mesh.colors, mesh.materials, mesh.instance_ids)
    return standing_on_floor(turned)


def standing_on_floor(mesh: Mesh) -> Mesh:
    """The mesh moved up or down so that its lowest point is on y = 0.

    Tilted legs and feet end in slanted faces whose lowest corner is awkward to place exactly;
    building them roughly and settling the whole model is simpler and exact.
    """
    positions = mesh.positions.copy()
    positions[:, 1] -= positions[:, 1].min()
    return Mesh(positions, mesh.normals, mesh.uvs, mesh.colors, mesh.materials, mesh.instance_ids)


def _cross(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """Cross product of two 3-vectors; numpy's general ``cross`` is slow for single vectors."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )
