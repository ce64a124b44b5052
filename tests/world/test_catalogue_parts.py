"""Part shapes: tilted beams, rings and arcs, outward-facing quads, settling on the floor."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vlln.world.catalogue.parts import (
    beam,
    facing_polygon,
    facing_quad,
    ring,
    rotated_about_x,
    shade,
    standing_on_floor,
)
from vlln.world.mesh import Mesh, MeshBuilder

RED = (0.8, 0.1, 0.1)


def unit_normals(mesh: Mesh) -> bool:
    return bool(np.allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-5))


def faces_point_outward(mesh: Mesh, centre: np.ndarray) -> bool:
    """For a convex solid: every triangle's normal points away from its centre."""
    tri_centres = mesh.positions.reshape(-1, 3, 3).mean(axis=1)
    normals = mesh.normals.reshape(-1, 3, 3)[:, 0]
    return bool((np.einsum("ij,ij->i", tri_centres - centre, normals) > 0).all())


def test_beam_runs_between_its_end_points_with_the_given_section() -> None:
    b = MeshBuilder()
    start, end = np.array([0.1, 0.2, 0.3]), np.array([0.5, 0.9, -0.2])
    beam(b, tuple(start), tuple(end), 0.06, 0.02, RED, 0, side=(0.0, 0.0, 1.0))
    mesh = b.build()
    assert mesh.n_triangles == 12 and unit_normals(mesh)
    run = (end - start) / np.linalg.norm(end - start)
    along = (mesh.positions - start) @ run
    assert along.min() == pytest.approx(0.0, abs=1e-6)
    assert along.max() == pytest.approx(np.linalg.norm(end - start), abs=1e-6)
    across = mesh.positions - start - np.outer(along, run)
    assert np.linalg.norm(across, axis=1).max() == pytest.approx(math.hypot(0.03, 0.01), abs=1e-6)
    assert faces_point_outward(mesh, (start + end) / 2)


def test_beam_needs_two_distinct_points() -> None:
    with pytest.raises(ValueError, match="distinct"):
        beam(MeshBuilder(), (0.0, 1.0, 0.0), (0.0, 1.0, 0.0), 0.1, 0.1, RED, 0)


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_ring_lies_between_its_radii_around_its_axis(axis: str) -> None:
    b = MeshBuilder()
    centre = np.array([0.2, 0.5, -0.1])
    ring(b, tuple(centre), 0.3, 0.05, 0.04, RED, 0, axis=axis, segments=12)
    mesh = b.build()
    assert unit_normals(mesh)
    k = "xyz".index(axis)
    offset = mesh.positions - centre
    height = offset[:, k]
    radial = np.linalg.norm(np.delete(offset, k, axis=1), axis=1)
    assert height.min() == pytest.approx(-0.02, abs=1e-6)
    assert height.max() == pytest.approx(0.02, abs=1e-6)
    assert radial.max() == pytest.approx(0.3, abs=1e-6)
    assert radial.min() >= 0.25 * math.cos(math.pi / 12) - 1e-6


def test_ring_arc_covers_only_its_angles() -> None:
    b = MeshBuilder()
    ring(b, (0.0, 0.0, 0.0), 0.1, 0.02, 0.02, RED, 0, axis="z", arc=(-math.pi / 2, math.pi / 2))
    positions = b.build().positions
    assert positions[:, 0].min() >= -1e-6  # the right half only, a handle on the +x side
    assert positions[:, 1].min() == pytest.approx(-0.1, abs=1e-6)
    assert positions[:, 1].max() == pytest.approx(0.1, abs=1e-6)


def test_ring_rejects_unknown_axes() -> None:
    with pytest.raises(ValueError, match="axis"):
        ring(MeshBuilder(), (0.0, 0.0, 0.0), 0.1, 0.02, 0.02, RED, 0, axis="w")


@pytest.mark.parametrize("outward", [(0.0, 0.0, 1.0), (0.0, 0.0, -1.0)])
def test_quads_and_polygons_face_the_requested_side(outward: tuple[float, float, float]) -> None:
    b = MeshBuilder()
    want = np.array(outward)
    facing_quad(b, np.zeros(3), np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), want, RED, 0)
    trapezoid = [np.array(p, np.float64) for p in ((0, 0, 0), (2, 0, 0), (1.5, 1, 0), (0.5, 1, 0))]
    facing_polygon(b, trapezoid, want, RED, 0)
    mesh = b.build()
    np.testing.assert_allclose(mesh.normals, np.tile(want, (len(mesh.normals), 1)), atol=1e-6)
    tris = mesh.positions.reshape(-1, 3, 3)
    winding = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    assert (winding @ want > 0).all(), "counter-clockwise seen from the front"
    assert sum(0.5 * np.linalg.norm(winding, axis=1)) == pytest.approx(1.0 + 1.5)


def test_rotated_about_x_tips_the_top_backwards_and_stays_on_the_floor() -> None:
    b = MeshBuilder()
    b.box((0.0, 0.5, 0.0), (0.1, 1.0, 0.1), RED, 0)
    tilted = rotated_about_x(b.build(), math.radians(20.0))
    top = tilted.positions[tilted.positions[:, 1].argmax()]
    assert top[2] < -0.25  # sin(20°) of a 1 m box, less half its depth
    assert tilted.positions[:, 1].min() == pytest.approx(0.0, abs=1e-6)
    assert unit_normals(tilted)


def test_standing_on_floor_moves_the_lowest_point_to_zero_without_changing_the_input() -> None:
    b = MeshBuilder()
    b.box((0.0, -0.3, 0.0), (0.2, 0.2, 0.2), RED, 0)
    mesh = b.build()
    settled = standing_on_floor(mesh)
    assert settled.positions[:, 1].min() == pytest.approx(0.0)
    assert mesh.positions[:, 1].min() == pytest.approx(-0.4)
    np.testing.assert_allclose(settled.positions[:, [0, 2]], mesh.positions[:, [0, 2]])


def test_shade_scales_and_clips() -> None:
    assert shade((0.5, 0.2, 0.9), 0.5) == pytest.approx((0.25, 0.1, 0.45))
    assert shade((0.5, 0.2, 0.9), 2.0) == pytest.approx((1.0, 0.4, 1.0))
