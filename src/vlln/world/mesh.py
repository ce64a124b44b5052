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

    def subdivided(self, times: int = 1) -> Mesh:
        """Every triangle split into four at its edge midpoints, ``times`` times over.

        The surface and its look stay the same while the triangle count grows by ``4**times``:
        how a procedural house becomes a test scene as dense as a real scan. The pieces of a
        triangle stay next to each other and keep its winding, material and instance.
        """
        mesh = self
        for _ in range(times):
            mesh = mesh._split_in_four()
        return mesh

    def _split_in_four(self) -> Mesh:
        normals = _split_floats(self.normals)
        lengths = np.linalg.norm(normals, axis=1, keepdims=True)
        return Mesh(
            _split_floats(self.positions),
            (normals / np.maximum(lengths, 1e-12)).astype(np.float32),
            _split_floats(self.uvs),
            _split_floats(self.colors),
            _split_labels(self.materials),
            _split_labels(self.instance_ids),
        )

    def bounds(self) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
        """Axis-aligned ``(min, max)`` corners of all vertices."""
        if len(self.positions) == 0:
            zero = np.zeros(3, np.float32)
            return zero, zero
        return self.positions.min(axis=0), self.positions.max(axis=0)


# Corners a, b, c and midpoints ab, bc, ca (numbered 0..5) make four triangles, all wound
# like their parent: (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca).
_FOUR_PIECES = np.array([0, 3, 5, 3, 1, 4, 5, 4, 2, 3, 4, 5])


def _split_floats(values: FloatArray) -> FloatArray:
    """Per-corner values of the four pieces of each triangle; midpoints take the average."""
    corners = values.reshape(-1, 3, values.shape[1])
    middles = (corners + np.roll(corners, -1, axis=1)) / 2
    six = np.concatenate([corners, middles.astype(np.float32)], axis=1)
    pieces: FloatArray = six[:, _FOUR_PIECES].reshape(-1, values.shape[1])
    return pieces


def _split_labels(values: NDArray[np.int32]) -> NDArray[np.int32]:
    """Per-corner labels (material, instance) of the four pieces: the parent's first one."""
    return np.repeat(values[::3], 12)


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
        self._quads(
            np.array([corner], np.float64),
            np.array([edge_u], np.float64),
            np.array([edge_v], np.float64),
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
        c, s = math.cos(yaw), math.sin(yaw)
        ex = np.array([c, 0.0, -s]) * size[0]
        ey = np.array([0.0, size[1], 0.0])
        ez = np.array([s, 0.0, c]) * size[2]
        origin = np.asarray(center, np.float64) - (ex + ey + ez) / 2.0
        sides = {
            "+x": (origin + ex, ey, ez),
            "-x": (origin, ez, ey),
            "+y": (origin + ey, ez, ex),
            "-y": (origin, ex, ez),
            "+z": (origin + ez, ex, ey),
            "-z": (origin, ey, ex),
        }
        chosen = [side for name, side in sides.items() if name in faces]
        if chosen:
            corners, us, vs = (np.array(part) for part in zip(*chosen, strict=True))
            self._quads(corners, us, vs, color, material)

    def _quads(
        self,
        corners: NDArray[np.float64],
        us: NDArray[np.float64],
        vs: NDArray[np.float64],
        color: Vec3,
        material: int,
    ) -> None:
        """Several parallelograms at once (one row each); degenerate ones are skipped."""
        normals = np.cross(us, vs)
        lengths = np.linalg.norm(normals, axis=1)
        keep = lengths > 0.0
        if not keep.all():
            corners, us, vs, normals, lengths = (
                a[keep] for a in (corners, us, vs, normals, lengths)
            )
        normals /= lengths[:, None]
        lu = np.linalg.norm(us, axis=1)
        lv = np.linalg.norm(vs, axis=1)
        zero = np.zeros_like(lu)
        p0, p1, p2, p3 = corners, corners + us, corners + us + vs, corners + vs
        t0, t1, t2, t3 = (
            np.stack(pair, axis=1) for pair in ((zero, zero), (lu, zero), (lu, lv), (zero, lv))
        )
        positions = np.stack([p0, p1, p2, p0, p2, p3], axis=1).reshape(-1, 3)
        uvs = np.stack([t0, t1, t2, t0, t2, t3], axis=1).reshape(-1, 2)
        self.add_triangles(positions, np.repeat(normals, 6, axis=0), uvs, color, material)

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
        zeros = np.zeros(segments)
        slope = (radius - top) / height if height > 0 else 0.0

        def ring(r: float, y: float, k: slice) -> NDArray[np.float64]:
            return np.stack([r * ca[k], zeros + y, r * sa[k]], axis=1)

        first, second = slice(0, segments), slice(1, segments + 1)
        b0, b1 = ring(radius, 0.0, first), ring(radius, 0.0, second)
        t0, t1 = ring(top, height, first), ring(top, height, second)
        scale = 1.0 / math.sqrt(1.0 + slope * slope)
        n0 = np.stack([ca[first], zeros + slope, sa[first]], axis=1) * scale
        n1 = np.stack([ca[second], zeros + slope, sa[second]], axis=1) * scale
        u0 = 2.0 * math.pi * max(radius, top) * np.arange(segments) / segments
        u1 = u0 + 2.0 * math.pi * max(radius, top) / segments
        low, high = zeros, zeros + height
        # Counter-clockwise seen from outside.
        positions = [np.stack([b0, t1, b1, b0, t0, t1], axis=1).reshape(-1, 3)]
        normals = [np.stack([n0, n1, n1, n0, n0, n1], axis=1).reshape(-1, 3)]
        uv_pairs = [(u0, low), (u1, high), (u1, low), (u0, low), (u0, high), (u1, high)]
        uvs = [np.stack([np.stack(p, axis=1) for p in uv_pairs], axis=1).reshape(-1, 2)]
        if caps:
            for r, y, up, rim_a, rim_b in ((top, height, 1.0, t1, t0), (radius, 0.0, -1.0, b0, b1)):
                if r <= 0:
                    continue
                centre = np.zeros((segments, 3))
                centre[:, 1] = y
                tri = np.stack([centre, rim_a, rim_b], axis=1).reshape(-1, 3)
                positions.append(tri)
                normals.append(np.tile((0.0, up, 0.0), (len(tri), 1)))
                uvs.append(tri[:, [0, 2]])
        pos, nor = _orient_axis(np.concatenate(positions), np.concatenate(normals), axis)
        self.add_triangles(pos + np.asarray(base_center), nor, np.concatenate(uvs), color, material)

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
        t, p = np.meshgrid(theta, phi, indexing="ij")
        unit = np.stack([np.sin(t) * np.cos(p), -np.cos(t), np.sin(t) * np.sin(p)], axis=-1)
        stretch = np.asarray(scale, np.float64)
        points = unit * radius * stretch
        bent = unit / stretch
        normals = bent / np.linalg.norm(bent, axis=-1, keepdims=True)
        tex = np.stack([radius * p, radius * (math.pi - t)], axis=-1)
        ring_grid, segment_grid = np.meshgrid(
            np.arange(last_ring), np.arange(segments), indexing="ij"
        )
        r, s = ring_grid.ravel(), segment_grid.ravel()
        corners = [(r, s), (r, s + 1), (r + 1, s + 1), (r + 1, s)]
        # At a pole two corners of a quad coincide: keep only the real triangle there.
        first = r != 0  # the north-pole row loses its (0, 1, 2) triangle
        second = r != rings - 1  # the south-pole row loses its (0, 2, 3) triangle
        rows, cols = [], []
        for keep, triangle in ((first, (0, 1, 2)), (second, (0, 2, 3))):
            for k in triangle:
                rows.append(corners[k][0][keep])
                cols.append(corners[k][1][keep])
        # Interleave so each triangle's three corners are consecutive.
        order_r = np.concatenate(
            [np.stack(rows[:3], axis=1).ravel(), np.stack(rows[3:], axis=1).ravel()]
        )
        order_c = np.concatenate(
            [np.stack(cols[:3], axis=1).ravel(), np.stack(cols[3:], axis=1).ravel()]
        )
        self.add_triangles(
            points[order_r, order_c] + np.asarray(center),
            normals[order_r, order_c],
            tex[order_r, order_c],
            color,
            material,
        )

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
