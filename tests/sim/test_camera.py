"""The pinhole camera: intrinsics, validation, pose matrices, back-projection, frustum test."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec
from vlln.world.frame import heading_vector


def project(
    spec: CameraSpec,
    point: NDArray[np.float64],
    position: tuple[float, float, float],
    yaw: float,
    tilt: float,
) -> tuple[float, float, float]:
    """Pixel (u, v) and z-depth of a world point, from the OpenGL matrices."""
    clip = spec.projection_matrix() @ spec.view_matrix(position, yaw, tilt) @ np.r_[point, 1.0]
    ndc = clip[:3] / clip[3]
    # Window coordinates; the projection flips y, so window row = image row v.
    u = (ndc[0] + 1.0) / 2.0 * spec.width - 0.5
    v = (ndc[1] + 1.0) / 2.0 * spec.height - 0.5
    return float(u), float(v), float(clip[3])


def test_default_intrinsics_follow_the_reference_camera() -> None:
    fx, fy, cx, cy = CameraSpec().intrinsics()
    assert fx == pytest.approx(320.0 / math.tan(math.radians(39.5)))
    assert fx == pytest.approx(388.19, abs=0.01)
    assert fy == fx
    assert (cx, cy) == (319.5, 239.5)


def test_intrinsics_scale_with_resolution_and_fov() -> None:
    narrow = CameraSpec(width=320, height=240, hfov_deg=60.0)
    fx, _, cx, cy = narrow.intrinsics()
    assert fx == pytest.approx(160.0 / math.tan(math.radians(30.0)))
    assert (cx, cy) == (159.5, 119.5)
    assert narrow.vfov_deg == pytest.approx(2 * math.degrees(math.atan(120.0 / fx)))


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("width", 0),
        ("height", -4),
        ("hfov_deg", 180.0),
        ("near", 0.0),
        ("far", 0.01),
        ("max_depth", 60.0),
        ("height_m", -1.0),
    ],
)
def test_invalid_settings_name_the_field(field: str, value: float) -> None:
    settings: dict[str, Any] = {field: value}
    with pytest.raises(ConfigError, match=field):
        CameraSpec(**settings)


def test_yaw_follows_the_world_frame() -> None:
    spec = CameraSpec()
    for yaw in (0.0, 0.7, math.pi / 2, -2.0):
        dx, dz = heading_vector(yaw)
        pose = spec.camera_to_world((1.0, 0.0, 2.0), yaw, 0.0)
        forward = -pose[:3, 2]
        np.testing.assert_allclose(forward, [dx, 0.0, dz], atol=1e-12)
        np.testing.assert_allclose(pose[:3, 3], [1.0, spec.height_m, 2.0])


def test_negative_tilt_looks_down() -> None:
    pose = CameraSpec().camera_to_world((0.0, 0.0, 0.0), 0.0, math.radians(-30.0))
    forward = -pose[:3, 2]
    assert forward[1] == pytest.approx(-0.5)
    assert forward[2] == pytest.approx(-math.cos(math.radians(30.0)))


def test_view_matrix_inverts_the_pose() -> None:
    spec = CameraSpec()
    args = ((0.3, 0.0, -1.2), 1.1, -0.4)
    np.testing.assert_allclose(
        spec.view_matrix(*args) @ spec.camera_to_world(*args), np.eye(4), atol=1e-12
    )


def test_projection_matrix_agrees_with_the_intrinsics() -> None:
    spec = CameraSpec()
    fx, fy, cx, cy = spec.intrinsics()
    position, yaw, tilt = (0.5, 0.0, 1.0), 0.4, -0.3
    rng = np.random.default_rng(3)
    for _ in range(20):
        camera_point = np.r_[rng.uniform(-1, 1, 2), -rng.uniform(0.5, 8.0)]
        world = spec.camera_to_world(position, yaw, tilt) @ np.r_[camera_point, 1.0]
        u, v, depth = project(spec, world[:3], position, yaw, tilt)
        assert depth == pytest.approx(-camera_point[2])
        assert u == pytest.approx(cx + fx * camera_point[0] / depth)
        # Rows grow downward: a point above the optical axis has v < cy.
        assert v == pytest.approx(cy - fy * camera_point[1] / depth)


def test_unproject_inverts_projection() -> None:
    spec = CameraSpec(width=320, height=240, hfov_deg=90.0)
    position, yaw, tilt = (2.0, 0.0, -1.0), -0.8, -0.5
    points = np.array([[2.5, 0.4, -3.0], [1.0, 1.8, -2.2], [3.0, 0.0, -4.0]])
    for point in points:
        u, v, depth = project(spec, point, position, yaw, tilt)
        np.testing.assert_allclose(
            spec.unproject(u, v, depth, position, yaw, tilt), point, atol=1e-9
        )


def test_unproject_is_vectorised() -> None:
    spec = CameraSpec()
    u = np.array([[0.0, 100.0], [639.0, 319.5]])
    v = np.array([[0.0, 50.0], [479.0, 239.5]])
    points = spec.unproject(u, v, np.full((2, 2), 2.0), (0.0, 0.0, 0.0), 0.3, -0.2)
    assert points.shape == (2, 2, 3)
    single = spec.unproject(100.0, 50.0, 2.0, (0.0, 0.0, 0.0), 0.3, -0.2)
    np.testing.assert_allclose(points[0, 1], single)


def test_centre_ray_tilted_down_hits_the_floor_at_h_over_sin() -> None:
    spec = CameraSpec()
    _, _, cx, cy = spec.intrinsics()
    tilt = math.radians(-30.0)
    depth = spec.height_m / math.sin(math.radians(30.0))
    point = spec.unproject(cx, cy, depth, (1.0, 0.0, 1.0), 0.0, tilt)
    assert point[1] == pytest.approx(0.0, abs=1e-12)
    assert point[2] == pytest.approx(1.0 - spec.height_m / math.tan(math.radians(30.0)))


def test_pixel_ray_has_unit_z_depth() -> None:
    spec = CameraSpec()
    rays = spec.pixel_ray(np.array([0.0, 639.0]), np.array([0.0, 479.0]))
    np.testing.assert_allclose(rays[:, 2], [-1.0, -1.0])
    fx, fy, cx, cy = spec.intrinsics()
    np.testing.assert_allclose(rays[0, :2], [-cx / fx, cy / fy])


def test_sphere_visibility_is_a_conservative_frustum_test() -> None:
    spec = CameraSpec()
    centres = np.array(
        [
            [0.0, 1.25, -5.0],  # straight ahead
            [0.0, 1.25, 5.0],  # behind
            [20.0, 1.25, -5.0],  # far to the right
            [4.6, 1.25, -5.0],  # just outside the right edge, but overlapping it
            [0.0, 1.25, -80.0],  # beyond the far plane
        ]
    )
    radii = np.array([0.5, 0.5, 0.5, 0.6, 1.0])
    visible, depth = spec.sphere_visibility(centres, radii, (0.0, 0.0, 0.0), 0.0)
    assert visible.tolist() == [True, False, False, True, False]
    np.testing.assert_allclose(depth, [5.0, -5.0, 5.0, 5.0, 80.0])


def test_image_size_must_be_whole_pixels() -> None:
    with pytest.raises(ConfigError, match="width: Input should be a valid integer"):
        CameraSpec(width=640.5)  # type: ignore[arg-type]
