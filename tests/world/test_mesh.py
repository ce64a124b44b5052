"""Primitives have the promised extents, outward normals, and transforms follow the frame."""

import math

import numpy as np
import pytest

from vlln.world.frame import heading_vector
from vlln.world.mesh import Mesh, MeshBuilder


def winding_agrees(mesh: Mesh) -> bool:
    tri = mesh.positions.reshape(-1, 3, 3)
    face = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    stored = mesh.normals.reshape(-1, 3, 3).mean(axis=1)
    return bool(np.all(np.einsum("ij,ij->i", face, stored) > 0))


@pytest.mark.parametrize(
    "build, lo, hi",
    [
        (lambda b: b.box((0, 0.5, 0), (1, 1, 2), (1, 0, 0), 0), (-0.5, 0, -1), (0.5, 1, 1)),
        (lambda b: b.cylinder((1, 0, 0), 0.5, 2.0, (1, 1, 1), 0), (0.5, 0, -0.5), (1.5, 2, 0.5)),
        (
            lambda b: b.cylinder((0, 0, 0), 0.5, 2.0, (1, 1, 1), 0, axis="x"),
            (0, -0.5, -0.5),
            (2, 0.5, 0.5),
        ),
        (lambda b: b.sphere((0, 1, 0), 0.5, (1, 1, 1), 0), (-0.5, 0.5, -0.5), (0.5, 1.5, 0.5)),
        (
            lambda b: b.sphere((0, 0, 0), 1.0, (1, 1, 1), 0, upper_half_only=True),
            (-1, 0, -1),
            (1, 1, 1),
        ),
    ],
)
def test_primitive_extent_and_outward_winding(build, lo, hi) -> None:
    builder = MeshBuilder()
    build(builder)
    mesh = builder.build()
    low, high = mesh.bounds()
    np.testing.assert_allclose(low, lo, atol=0.06)
    np.testing.assert_allclose(high, hi, atol=0.06)
    assert winding_agrees(mesh)
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-5)


def test_transformed_rotates_the_front_like_the_agent_frame() -> None:
    builder = MeshBuilder()
    builder.box((0.0, 0.0, -1.0), (0.1, 0.1, 0.1), (1, 1, 1), 0)  # a marker in front (-z)
    yaw = math.radians(90)
    moved = builder.build().transformed(yaw, (2.0, 0.0, 3.0))
    centre = moved.positions.mean(axis=0)
    dx, dz = heading_vector(yaw)
    np.testing.assert_allclose(centre, (2.0 + dx, 0.0, 3.0 + dz), atol=1e-5)


def test_concatenate_and_instance_ids() -> None:
    a = MeshBuilder()
    a.box((0, 0, 0), (1, 1, 1), (1, 1, 1), 0)
    b = MeshBuilder()
    b.sphere((0, 0, 0), 1.0, (1, 1, 1), 0)
    mesh = Mesh.concatenate([a.build().with_instance_id(3), b.build().with_instance_id(7)])
    assert mesh.n_triangles == 12 + b.build().n_triangles
    assert set(np.unique(mesh.instance_ids)) == {3, 7}


def test_subdivided_keeps_the_surface_and_its_attributes() -> None:
    builder = MeshBuilder()
    builder.box((0.0, 0.5, 0.0), (1.0, 1.0, 2.0), (0.2, 0.4, 0.6), 3)
    builder.sphere((2.0, 1.0, 0.0), 0.5, (0.9, 0.1, 0.1), 5)
    mesh = builder.build().with_instance_id(4)
    fine = mesh.subdivided(2)

    def area(m: Mesh) -> float:
        tri = m.positions.reshape(-1, 3, 3).astype(np.float64)
        return float(
            np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
        )

    assert fine.n_triangles == 16 * mesh.n_triangles
    assert area(fine) == pytest.approx(area(mesh), rel=1e-5)
    assert winding_agrees(fine)
    np.testing.assert_array_equal(fine.bounds()[0], mesh.bounds()[0])
    # The 16 pieces of a triangle follow each other and keep its material and instance.
    assert np.array_equal(fine.materials.reshape(-1, 48)[:, 0], mesh.materials[::3])
    assert np.all(fine.materials.reshape(-1, 48) == fine.materials.reshape(-1, 48)[:, :1])
    assert np.all(fine.instance_ids == 4)
    pieces_mean = fine.colors.reshape(-1, 48, 3).mean(axis=1)
    assert np.allclose(pieces_mean, mesh.colors.reshape(-1, 3, 3).mean(axis=1), atol=1e-6)
    assert mesh.subdivided(0) is mesh
