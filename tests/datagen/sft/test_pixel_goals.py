"""Which pixel of a real look-down image shows a point, and when none does."""

from __future__ import annotations

import numpy as np
import pytest
from tests.datagen.sft.conftest import HandDataset

from vlln.datagen.layout import HouseDataset
from vlln.datagen.sft.pixel_goals import project_point, visible_pixel
from vlln.sim.camera import CameraSpec
from vlln.world.frame import quaternion_to_yaw

SPEC = CameraSpec()


@pytest.fixture(scope="module")
def golden_frame(hand_dataset: HandDataset) -> tuple[dict[str, np.ndarray], np.ndarray]:
    dataset = HouseDataset(hand_dataset.root / "trajectories" / hand_dataset.house)
    return dataset.frames(0), dataset.depth("down", 0, 2)


def test_a_drawn_surface_point_is_found_at_its_pixel_and_hidden_ones_are_not(
    golden_frame: tuple[dict[str, np.ndarray], np.ndarray],
) -> None:
    frames, depth = golden_frame
    eye, rotation = frames["down_camera_position"][2], frames["down_camera_rotation"][2]
    yaw = quaternion_to_yaw(list(frames["agent_rotation"][2]))
    feet = frames["agent_position"][2]
    for u, v in [(320, 400), (100, 300), (600, 460)]:
        surface = SPEC.unproject(u, v, depth[v, u], feet, yaw, np.radians(-30.0))
        assert visible_pixel(SPEC, eye, rotation, depth, surface, 0.1) == (u, v)
        behind = SPEC.unproject(u, v, depth[v, u] + 0.5, feet, yaw, np.radians(-30.0))
        assert visible_pixel(SPEC, eye, rotation, depth, behind, 0.1) is None
        pu, pv, z = project_point(SPEC, eye, rotation, behind)
        assert (pu, pv, z) == pytest.approx((u, v, depth[v, u] + 0.5), abs=1e-4)


def test_points_behind_or_beside_the_camera_have_no_pixel(
    golden_frame: tuple[dict[str, np.ndarray], np.ndarray],
) -> None:
    frames, depth = golden_frame
    eye, rotation = frames["down_camera_position"][2], frames["down_camera_rotation"][2]
    feet = frames["agent_position"][2]
    yaw = quaternion_to_yaw(list(frames["agent_rotation"][2]))
    ahead = np.array([-np.sin(yaw), 0.0, -np.cos(yaw)])
    left = np.array([-np.cos(yaw), 0.0, np.sin(yaw)])
    assert visible_pixel(SPEC, eye, rotation, depth, feet - ahead, 0.1) is None
    assert project_point(SPEC, eye, rotation, feet - ahead)[2] < 0.0
    assert visible_pixel(SPEC, eye, rotation, depth, feet + ahead + 3.0 * left, 0.1) is None
    assert visible_pixel(SPEC, eye, rotation, depth, feet + 0.25 * ahead, 0.1) is None
    assert visible_pixel(SPEC, eye, rotation, depth, feet + ahead, 0.1) is not None
