from __future__ import annotations

import math

import pytest

from tests.sim import scenes
from vlln.errors import ConfigError
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.viewpoints import view_points
from vlln.world.model import Box3

TABLE = Box3((1.4, 0.0, 1.6), (2.6, 0.75, 2.4))  # the table of the furnished room


@pytest.fixture(scope="module")
def grid() -> NavGrid:
    return NavGrid.from_mesh(scenes.furnished_room())


def test_view_points_are_navigable_and_inside_the_expanded_box(grid: NavGrid) -> None:
    points = view_points(grid, TABLE)
    assert points
    big = TABLE.expanded(0.6)
    for x, z in points:
        assert grid.is_navigable(x, z)
        assert big.min[0] <= x <= big.max[0] and big.min[2] <= z <= big.max[2]


def test_view_points_are_all_navigable_cells_of_the_footprint(grid: NavGrid) -> None:
    points = set(view_points(grid, TABLE))
    big = TABLE.expanded(0.6)
    for row, col in grid.free_cells().tolist():
        x, z = grid.cell_to_world(row, col)
        inside = (
            big.min[0] + 1e-9 < x < big.max[0] - 1e-9 and big.min[2] + 1e-9 < z < big.max[2] - 1e-9
        )
        if inside:
            assert (x, z) in points


def test_view_points_come_in_a_fixed_row_major_order(grid: NavGrid) -> None:
    points = view_points(grid, TABLE)
    assert points == view_points(grid, TABLE)
    keys = [(z, x) for x, z in points]
    assert keys == sorted(keys)


def test_stride_subsamples_on_grid_indices(grid: NavGrid) -> None:
    full = view_points(grid, TABLE)
    sparse = view_points(grid, TABLE, stride=3)
    assert set(sparse) <= set(full)
    assert len(full) / 12 < len(sparse) < len(full) / 6
    for x, z in sparse:
        row, col = grid.world_to_cell(x, z)
        assert row % 3 == 0 and col % 3 == 0


def test_view_points_of_an_object_against_walls_exist_and_are_reachable(grid: NavGrid) -> None:
    wardrobe = Box3((5.9, 0.0, 0.7), (7.1, 2.0, 1.3))
    points = view_points(grid, wardrobe)
    assert points
    field = GeodesicField(grid, points)
    assert math.isfinite(field.distance(2.0, 4.0))


def test_a_box_off_the_grid_has_no_view_points_and_bad_settings_fail(grid: NavGrid) -> None:
    far = Box3((50.0, 0.0, 50.0), (51.0, 1.0, 51.0))
    assert view_points(grid, far) == []
    with pytest.raises(ConfigError, match="margin"):
        view_points(grid, TABLE, margin=-0.1)
    with pytest.raises(ConfigError, match="stride"):
        view_points(grid, TABLE, stride=0)
