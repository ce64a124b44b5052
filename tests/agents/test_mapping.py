import math

import numpy as np
import pytest

from tests.sim import scenes
from vlln.agents.frontier.mapping import MapConfig, ObstacleMap, Pose
from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Renderer


@pytest.fixture(scope="module")
def room_map() -> ObstacleMap:
    """One real frame of the empty 6 x 4 m room, from (1, 2) looking east (+x)."""
    camera = CameraSpec()
    with Renderer(scenes.empty_room(), camera) as renderer:
        frame = renderer.render((1.0, 0.0, 2.0), -math.pi / 2, 0.0)
    obstacle_map = ObstacleMap(camera)
    new = obstacle_map.update(frame.depth, Pose(1.0, 2.0, -math.pi / 2), 0.0)
    assert new.size > 0
    return obstacle_map


def _cell(obstacle_map: ObstacleMap, x: float, z: float) -> tuple[int, int]:
    return obstacle_map.cell_of(x, z)


def test_the_wall_ahead_is_an_obstacle(room_map: ObstacleMap) -> None:
    # The east wall's inner face is at x = 5.95; the camera sees it from z ~ 0.3 to 3.7.
    for z in (1.0, 1.5, 2.0, 2.5, 3.0):
        row, col = _cell(room_map, 5.97, z)
        assert room_map.obstacle[row, col - 1 : col + 1].any()


def test_floor_up_to_the_wall_is_explored_free_and_behind_it_unknown(
    room_map: ObstacleMap,
) -> None:
    for x in np.arange(1.5, 5.7, 0.2):
        row, col = _cell(room_map, float(x), 2.0)
        assert room_map.explored[row, col] and not room_map.obstacle[row, col]
    row, col = _cell(room_map, 6.5, 2.0)
    assert not room_map.explored[row, col]
    row, col = _cell(room_map, 0.5, 2.0)  # behind the camera
    assert not room_map.explored[row, col]


def test_a_bump_marks_the_cells_ahead(room_map: ObstacleMap) -> None:
    obstacle_map = ObstacleMap(CameraSpec())
    obstacle_map.mark_blocked_ahead(Pose(0.0, 0.0, 0.0), 0.3, 0.1)  # yaw 0 looks along -z
    ahead = obstacle_map.cell_of(0.0, -0.35)
    behind = obstacle_map.cell_of(0.0, 0.35)
    assert obstacle_map.obstacle[ahead] and not obstacle_map.obstacle[behind]


def test_invalid_configs_are_rejected() -> None:
    with pytest.raises(ConfigError, match="cell_size"):
        MapConfig(cell_size=2.0)
    with pytest.raises(ConfigError, match="obstacle_band"):
        MapConfig(obstacle_band=(0.05, 1.5))
