"""Triangle meshes built from primitives.

A :class:`Mesh` is a triangle soup (three vertices per triangle, no index buffer) with
per-vertex normal, colour, texture coordinate, material and instance id. A whole house is one
such mesh, uploaded to the renderer as one vertex buffer and drawn with one call.

Texture coordinates are in metres along the surface, so procedural textures (wood grain,
tiles, fabric weave) have the same scale on every object.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Vec3 = tuple[float, float, float]
FloatArray = NDArray[np.float32]


@dataclass
class Mesh:
    """A triangle soup; every array has one row per vertex, ``3 * n_triangles`` rows."""

    positions: FloatArray  # (n, 3) metres
    normals: FloatArray  # (n, 3) unit
    uvs: FloatArray  # (n, 2) metres along the surface
    colors: FloatArray  # (n, 3) linear RGB in [0, 1]
    materials: NDArray[np.int32]  # (n,) index into vlln.world.materials.MATERIALS
    instance_ids: NDArray[np.int32]  # (n,) object id, or a negative StructureId

    @staticmethod
    def empty() -> Mesh:
        return Mesh(
            np.zeros((0, 3), np.float32),
            np.zeros((0, 3), np.float32),
            np.zeros((0, 2), np.float32),
            np.zeros((0, 3), np.float32),
            np.zeros(0, np.int32),
            np.zeros(0, np.int32),
        )

    @property
    def n_triangles(self) -> int:
        return len(self.positions) // 3

    @staticmethod
    def concatenate(meshes: list[Mesh]) -> Mesh:
        if not meshes:
            return Mesh.empty()
        return Mesh(
            np.concatenate([m.positions for m in meshes]),
            np.concatenate([m.normals for m in meshes]),
            np.concatenate([m.uvs for m in meshes]),
            np.concatenate([m.colors for m in meshes]),
            np.concatenate([m.materials for m in meshes]),
            np.concatenate([m.instance_ids for m in meshes]),
        )

    def transformed(self, yaw: float, offset: Vec3) -> Mesh:
        """This mesh rotated by ``yaw`` about +y (see :mod:`vlln.world.frame`), then moved."""
        c, s = math.cos(yaw), math.sin(yaw)
        # Rotation about +y by yaw: x' = c x + s z, z' = -s x + c z (yaw 0 looks along -z).
        rotation = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]], np.float32)
        positions = self.positions @ rotation.T + np.asarray(offset, np.float32)
        normals = self.normals @ rotation.T
        return Mesh(positions, normals, self.uvs, self.colors, self.materials, self.instance_ids)

    def with_instance_id(self, instance_id: int) -> Mesh:
        ids = np.full(len(self.positions), instance_id, np.int32)
        return Mesh(self.positions, self.normals, self.uvs, self.colors, self.materials, ids)

    def bounds(self) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
        """Axis-aligned ``(min, max)`` corners of all vertices."""
        if len(self.positions) == 0:
            zero = np.zeros(3, np.float32)
            return zero, zero
        return self.positions.min(axis=0), self.positions.max(axis=0)


class MeshBuilder:
    """Collects primitives (boxes, cylinders, spheres, ...) into one :class:`Mesh`.

    Every primitive takes a colour (linear RGB) and a material index; the instance id is set
    once for the whole model with :meth:`Mesh.with_instance_id`.
    """

    def __init__(self) -> None:
        self._positions: list[NDArray[np.float32]] = []
        self._normals: list[NDArray[np.float32]] = []
        self._uvs: list[NDArray[np.float32]] = []
        self._colors: list[NDArray[np.float32]] = []
        self._materials: list[NDArray[np.int32]] = []

    def add_triangles(
        self,
        positions: NDArray[np.floating],
        normals: NDArray[np.floating],
        uvs: NDArray[np.floating],
        color: Vec3,
        material: int,
    ) -> None:
        """Append raw triangles (``n`` vertices, ``n`` divisible by 3)."""
        n = len(positions)
        self._positions.append(np.asarray(positions, np.float32).reshape(n, 3))
        self._normals.append(np.asarray(normals, np.float32).reshape(n, 3))
        self._uvs.append(np.asarray(uvs, np.float32).reshape(n, 2))
        self._colors.append(np.tile(np.asarray(color, np.float32), (n, 1)))
        self._materials.append(np.full(n, material, np.int32))

    def quad(self, corner: Vec3, edge_u: Vec3, edge_v: Vec3, color: Vec3, material: int) -> None:
        """A parallelogram ``corner + a*edge_u + b*edge_v``; it faces ``edge_u x edge_v``."""
        p0 = np.asarray(corner, np.float64)
        u = np.asarray(edge_u, np.float64)
        v = np.asarray(edge_v, np.float64)
        normal = np.cross(u, v)
        length = np.linalg.norm(normal)
        if length == 0.0:
            return
        normal /= length
        lu, lv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
        corners = [p0, p0 + u, p0 + u + v, p0 + v]
        tex = [(0.0, 0.0), (lu, 0.0), (lu, lv), (0.0, lv)]
        order = [0, 1, 2, 0, 2, 3]
        self.add_triangles(
            np.array([corners[i] for i in order]),
            np.tile(normal, (6, 1)),
            np.array([tex[i] for i in order]),
            color,
            material,
        )

    def box(
        self,
        center: Vec3,
        size: Vec3,
        color: Vec3,
        material: int,
        yaw: float = 0.0,
        faces: str = "+x-x+y-y+z-z",
    ) -> None:
        """An axis-aligned box (then rotated by ``yaw`` about its centre); ``faces`` picks sides."""
        hx, hy, hz = (s / 2.0 for s in size)
        c, s = math.cos(yaw), math.sin(yaw)
        ex = np.array([c, 0.0, -s]) * 2 * hx
        ey = np.array([0.0, 1.0, 0.0]) * 2 * hy
        ez = np.array([s, 0.0, c]) * 2 * hz
        origin = np.asarray(center, np.float64) - (ex + ey + ez) / 2.0
        sides = {
            "+x": (origin + ex, ey, ez),
            "-x": (origin, ez, ey),
            "+y": (origin + ey, ez, ex),
            "-y": (origin, ex, ez),
            "+z": (origin + ez, ex, ey),
            "-z": (origin, ey, ex),
        }
        for name, (corner, u, v) in sides.items():
            if name in faces:
                self.quad(tuple(corner), tuple(u), tuple(v), color, material)

    def cylinder(
        self,
        base_center: Vec3,
        radius: float,
        height: float,
        color: Vec3,
        material: int,
        segments: int = 12,
        radius_top: float | None = None,
        caps: bool = True,
        axis: str = "y",
    ) -> None:
        """A vertical cylinder or frustum (``radius_top`` differs), optionally along x or z."""
        top = radius if radius_top is None else radius_top
        angles = np.linspace(0.0, 2.0 * math.pi, segments + 1)
        ca, sa = np.cos(angles), np.sin(angles)
        slope = (radius - top) / height if height > 0 else 0.0
        positions: list[NDArray[np.float64]] = []
        normals: list[NDArray[np.float64]] = []
        uvs: list[tuple[float, float]] = []
        circumference = 2.0 * math.pi * max(radius, top)
        for i in range(segments):
            b0 = np.array([radius * ca[i], 0.0, radius * sa[i]])
            b1 = np.array([radius * ca[i + 1], 0.0, radius * sa[i + 1]])
            t0 = np.array([top * ca[i], height, top * sa[i]])
            t1 = np.array([top * ca[i + 1], height, top * sa[i + 1]])
            n0 = _unit(np.array([ca[i], slope, sa[i]]))
            n1 = _unit(np.array([ca[i + 1], slope, sa[i + 1]]))
            u0 = circumference * i / segments
            u1 = circumference * (i + 1) / segments
            # Counter-clockwise seen from outside.
            positions += [b0, t1, b1, b0, t0, t1]
            normals += [n0, n1, n1, n0, n0, n1]
            uvs += [(u0, 0.0), (u1, height), (u1, 0.0), (u0, 0.0), (u0, height), (u1, height)]
            if caps:
                for y, r, up in ((height, top, 1.0), (0.0, radius, -1.0)):
                    if r <= 0:
                        continue
                    centre = np.array([0.0, y, 0.0])
                    p0 = np.array([r * ca[i], y, r * sa[i]])
                    p1 = np.array([r * ca[i + 1], y, r * sa[i + 1]])
                    tri = [centre, p1, p0] if up > 0 else [centre, p0, p1]
                    positions += tri
                    normals += [np.array([0.0, up, 0.0])] * 3
                    uvs += [(float(p[0]), float(p[2])) for p in tri]
        pos = np.array(positions)
        nor = np.array(normals)
        pos, nor = _orient_axis(pos, nor, axis)
        self.add_triangles(pos + np.asarray(base_center), nor, np.array(uvs), color, material)

    def sphere(
        self,
        center: Vec3,
        radius: float,
        color: Vec3,
        material: int,
        segments: int = 10,
        scale: Vec3 = (1.0, 1.0, 1.0),
        upper_half_only: bool = False,
    ) -> None:
        """A UV sphere (an ellipsoid when ``scale`` differs per axis)."""
        rings = max(4, 2 * (segments // 4))  # even, so a hemisphere ends exactly at y = 0
        last_ring = rings // 2 if upper_half_only else rings
        theta = np.linspace(0.0, math.pi, rings + 1)[::-1]  # from the north pole (+y) down
        phi = np.linspace(0.0, 2.0 * math.pi, segments + 1)
        sx, sy, sz = scale
        positions: list[NDArray[np.float64]] = []
        normals: list[NDArray[np.float64]] = []
        uvs: list[tuple[float, float]] = []

        def point(t: float, p: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
            unit = np.array([math.sin(t) * math.cos(p), -math.cos(t), math.sin(t) * math.sin(p)])
            pos = unit * radius * np.array([sx, sy, sz])
            return pos, _unit(unit / np.array([sx, sy, sz]))

        for r in range(last_ring):
            for s in range(segments):
                quad = [(r, s), (r, s + 1), (r + 1, s + 1), (r + 1, s)]
                pts = [point(theta[a], phi[b]) for a, b in quad]
                # At a pole two corners of the quad coincide: keep only the real triangle.
                corners = (
                    (0, 2, 3) if r == 0 else (0, 1, 2) if r == rings - 1 else (0, 1, 2, 0, 2, 3)
                )
                for k in corners:
                    positions.append(pts[k][0])
                    normals.append(pts[k][1])
                    a, b = quad[k]
                    uvs.append((radius * phi[b], radius * (math.pi - theta[a])))
        pos = np.array(positions) + np.asarray(center)
        self.add_triangles(pos, np.array(normals), np.array(uvs), color, material)

    def build(self) -> Mesh:
        if not self._positions:
            return Mesh.empty()
        return Mesh(
            np.concatenate(self._positions),
            np.concatenate(self._normals),
            np.concatenate(self._uvs),
            np.concatenate(self._colors),
            np.concatenate(self._materials),
            np.zeros(sum(len(p) for p in self._positions), np.int32),
        )


def _unit(v: NDArray[np.float64]) -> NDArray[np.float64]:
    norm = float(np.linalg.norm(v))
    return v / norm if norm > 0 else v


def _orient_axis(
    positions: NDArray[np.float64], normals: NDArray[np.float64], axis: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Turn geometry built along +y so that it runs along ``axis`` (``"x"``, ``"y"``, ``"z"``)."""
    if axis == "y":
        return positions, normals
    if axis == "x":  # y -> x, x -> -y: a rotation about z
        perm = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    elif axis == "z":  # y -> z, z -> -y: a rotation about x
        perm = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    else:
        raise ValueError(f"axis must be 'x', 'y' or 'z', not {axis!r}")
    return positions @ perm.T, normals @ perm.T
