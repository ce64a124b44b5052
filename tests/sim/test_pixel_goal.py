"""Pixel goals: a pixel on a rendered look-down frame leads back to the floor point it shows."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from vlln.sim.agent import AgentState
from vlln.sim.pixel_goal import pixel_floor_goal, pixel_world_point
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.world.frame import heading_vector

TILT_DOWN = -math.radians(30.0)


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    cache = SceneCache()
    yield cache.get(procedural_scene_id(2))
    cache.close()


def project(sim: Simulator, point: np.ndarray, state: AgentState) -> tuple[int, int, float]:
    """Nearest pixel and z-depth of a world point, from the camera's view matrix."""
    spec = sim.config.camera
    fx, fy, cx, cy = spec.intrinsics()
    local = spec.view_matrix(state.position, state.yaw, state.tilt) @ np.r_[point, 1.0]
    depth = -float(local[2])
    col = round(cx + fx * float(local[0]) / depth)
    row = round(cy - fy * float(local[1]) / depth)
    return col, row, depth


@pytest.mark.slow
def test_a_pixel_on_a_known_floor_point_lands_within_15_cm_of_it(sim: Simulator) -> None:
    rng = np.random.default_rng(7)
    component = sim.grid.largest_component()
    spec = sim.config.camera
    checked = 0
    worst = 0.0
    for _ in range(400):
        x, z = sim.grid.sample_navigable_point(rng, component)
        yaw = float(rng.uniform(-math.pi, math.pi))
        ahead = float(rng.uniform(1.2, 3.5))
        side = float(rng.uniform(-0.8, 0.8))
        dx, dz = heading_vector(yaw)
        gx, gz = x + ahead * dx - side * dz, z + ahead * dz + side * dx
        if not sim.grid.is_navigable(gx, gz):
            continue
        state = AgentState((x, 0.0, z), yaw, TILT_DOWN)
        frame = sim.render(state)
        floor_point = np.array([gx, 0.0, gz])
        col, row, depth = project(sim, floor_point, state)
        if not (0 <= col < spec.width and 0 <= row < spec.height):
            continue
        if abs(float(frame.depth[row, col]) - depth) > 0.05:
            continue  # hidden behind furniture: not a floor pixel
        goal = pixel_floor_goal(spec, sim.grid, frame.depth, col, row, state)
        assert goal is not None
        error = math.hypot(goal[0] - gx, goal[1] - gz)
        worst = max(worst, error)
        assert error < 0.15, (x, z, yaw, col, row, error)
        checked += 1
        if checked == 60:
            break
    assert checked == 60, f"only {checked} poses had a visible floor point"
    assert worst > 0.0


def test_a_pixel_on_furniture_snaps_to_navigable_floor_nearby(sim: Simulator) -> None:
    rng = np.random.default_rng(3)
    spec = sim.config.camera
    found = 0
    for _ in range(200):
        x, z = sim.grid.sample_navigable_point(rng, sim.grid.largest_component())
        state = AgentState((x, 0.0, z), float(rng.uniform(-math.pi, math.pi)), TILT_DOWN)
        frame = sim.render(state)
        point = pixel_world_point(spec, frame.depth, 320, 300, state)
        if point is None or point[1] < 0.3:
            continue  # want a pixel that shows something standing on the floor
        goal = pixel_floor_goal(spec, sim.grid, frame.depth, 320, 300, state)
        assert goal is not None
        assert sim.grid.is_navigable(*goal)
        assert math.hypot(goal[0] - point[0], goal[1] - point[2]) < 1.5
        found += 1
        if found == 5:
            break
    assert found == 5


def test_pixels_outside_the_image_or_showing_nothing_give_no_goal(sim: Simulator) -> None:
    spec = sim.config.camera
    state = AgentState((0.0, 0.0, 0.0), 0.0, TILT_DOWN)
    depth = np.zeros((spec.height, spec.width), np.float32)
    assert pixel_floor_goal(spec, sim.grid, depth, 10, 10, state) is None
    depth[:] = 2.0
    assert pixel_floor_goal(spec, sim.grid, depth, spec.width, 10, state) is None
    assert pixel_floor_goal(spec, sim.grid, depth, 10, -1, state) is None
