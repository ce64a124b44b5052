from __future__ import annotations

import math

import numpy as np
import pytest

from tests.sim import scenes
from vlln.errors import ConfigError, NavigationError
from vlln.sim.navgrid import NavGrid
from vlln.world.mesh import Mesh, MeshBuilder

RADIUS = 0.18
CELL = 0.05


def _rect_distance(x: float, z: float, x0: float, z0: float, x1: float, z1: float) -> float:
    dx = max(x0 - x, 0.0, x - x1)
    dz = max(z0 - z, 0.0, z - z1)
    return math.hypot(dx, dz)


def _centres(grid: NavGrid) -> np.ndarray:
    cells = grid.free_cells()
    return np.array([grid.cell_to_world(int(r), int(c)) for r, c in cells])


def test_empty_room_area_matches_the_room_shrunk_by_the_radius() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))
    # Inner faces of the walls at 0.05 and width - 0.05; the body keeps RADIUS from them.
    inner = 0.05 + RADIUS
    width, depth = 6.0 - 2 * inner, 4.0 - 2 * inner
    tolerance = 2 * (width + depth) * 2 * CELL  # up to two cells of rounding per side
    assert abs(grid.navigable_area - width * depth) < tolerance
    assert grid.components()[1] == 1
    assert grid.is_navigable(3.0, 2.0)
    assert not grid.is_navigable(0.1, 2.0)  # inside the clearance of the west wall
    assert not grid.is_navigable(-5.0, 2.0)  # off the grid


def test_navigable_cells_keep_the_radius_from_every_obstacle() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room(), agent_radius=RADIUS, cell_size=CELL)
    # Footprints of the blocking boxes (table, wardrobe) and the inner wall faces.
    boxes = [(1.4, 1.6, 2.6, 2.4), (5.9, 0.7, 7.1, 1.3)]
    slack = CELL / math.sqrt(2.0)  # a blocked cell's centre is within this of its geometry
    for x, z in _centres(grid):
        for box in boxes:
            assert _rect_distance(x, z, *box) > RADIUS - slack
        assert 0.05 + RADIUS - slack < x < 7.95 - RADIUS + slack
        assert 0.05 + RADIUS - slack < z < 5.95 - RADIUS + slack


def test_free_floor_far_from_obstacles_is_navigable() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    margin = RADIUS + 2 * CELL
    rng = np.random.default_rng(3)
    checked = 0
    for x, z in rng.uniform((0.0, 0.0), (8.0, 6.0), size=(2000, 2)):
        far_from_walls = 0.05 + margin < x < 7.95 - margin and 0.05 + margin < z < 5.95 - margin
        obstacles = [
            _rect_distance(x, z, 1.4, 1.6, 2.6, 2.4),  # table
            _rect_distance(x, z, 5.9, 0.7, 7.1, 1.3),  # wardrobe
            _rect_distance(x, z, 3.9, 1.6, 5.1, 2.4),  # rotated cabinet (its bounding box)
            math.hypot(x - 1.5, z - 4.5) - 0.25,  # stool
        ]
        if far_from_walls and min(obstacles) > margin:
            assert grid.is_navigable(x, z), (x, z)
            checked += 1
    assert checked > 500


def _segment_meets_square(
    a: tuple[float, float], b: tuple[float, float], lo: tuple[float, float], size: float
) -> bool:
    """Liang-Barsky clipping of segment a-b against a closed axis-aligned square."""
    t0, t1 = 0.0, 1.0
    for axis in (0, 1):
        d = b[axis] - a[axis]
        for p, q in ((-d, a[axis] - lo[axis]), (d, lo[axis] + size - a[axis])):
            if p == 0.0:
                if q < 0.0:
                    return False
            elif p < 0.0:
                t0 = max(t0, q / p)
            else:
                t1 = min(t1, q / p)
    return t0 <= t1


def _rectangle_meets_square(
    corners: list[tuple[float, float]], lo: tuple[float, float], size: float
) -> bool:
    """Separating axes of a (rotated) rectangle and a closed axis-aligned square."""
    square = [
        (lo[0], lo[1]),
        (lo[0] + size, lo[1]),
        (lo[0], lo[1] + size),
        (lo[0] + size, lo[1] + size),
    ]
    (x0, z0), (x1, z1), (x2, z2) = corners[:3]
    for ax, az in ((1.0, 0.0), (0.0, 1.0), (x1 - x0, z1 - z0), (x2 - x1, z2 - z1)):
        a = [ax * x + az * z for x, z in corners]
        b = [ax * x + az * z for x, z in square]
        if max(a) < min(b) or max(b) < min(a):
            return False
    return True


def test_obstacle_cells_are_exactly_the_columns_the_geometry_meets() -> None:
    # With no radius the navigable cells are the floor minus the raw obstacle cells.
    panel, ramp, slope = MeshBuilder(), MeshBuilder(), MeshBuilder()
    a, b = (1.03, 1.07), (3.51, 2.94)
    panel.quad((a[0], 0.0, a[1]), (b[0] - a[0], 0.0, b[1] - a[1]), (0.0, 2.0, 0.0), (1, 1, 1), 0)
    # Rises 3 m over x in [3.52, 5.52]: inside the band (0.15, 1.5] for x in (3.62, 4.52].
    ramp.quad((3.52, 0.0, 3.53), (0.0, 0.0, 1.94), (2.0, 3.0, 0.0), (1, 1, 1), 0)
    # Rises 3 m over 2 m along the diagonal direction r; 1.5 m wide along w.
    r, w, c = (0.8, 0.6), (-0.6, 0.8), (3.61, 0.43)
    slope.quad(
        (c[0], 0.0, c[1]), (1.5 * w[0], 0.0, 1.5 * w[1]), (2 * r[0], 3.0, 2 * r[1]), (1, 1, 1), 0
    )
    in_band = [  # its part in the band lies 0.1 to 1.0 m up the slope
        (c[0] + t * r[0] + u * w[0], c[1] + t * r[1] + u * w[1])
        for t, u in ((0.1, 0.0), (1.0, 0.0), (1.0, 1.5), (0.1, 1.5))
    ]
    mesh = Mesh.concatenate(
        [
            scenes.floor(0.0, 0.0, 6.0, 6.0),
            panel.build().with_instance_id(1),
            ramp.build().with_instance_id(2),
            slope.build().with_instance_id(3),
        ]
    )
    grid = NavGrid.from_mesh(mesh, agent_radius=0.0)
    for row, col in np.ndindex(grid.shape):
        x, z = grid.cell_to_world(row, col)
        if not (0.1 < x < 5.9 and 0.1 < z < 5.9):
            continue
        lo = (x - CELL / 2, z - CELL / 2)
        on_panel = _segment_meets_square(a, b, lo, CELL)
        on_ramp = lo[0] <= 4.52 and lo[0] + CELL > 3.62 and lo[1] <= 5.47 and lo[1] + CELL >= 3.53
        on_slope = _rectangle_meets_square(in_band, lo, CELL)
        assert grid.navigable[row, col] == (not (on_panel or on_ramp or on_slope)), (x, z)


def test_low_and_high_objects_do_not_block_but_hollow_ones_do() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    assert grid.is_navigable(4.0, 4.5)  # over the 2 cm rug
    assert grid.is_navigable(7.0, 5.0)  # under the shelf hanging at 1.7 m
    # The wardrobe is an open-bottomed hollow box; its inside must not be an island.
    for x, z in [(6.5, 1.0), (6.3, 0.95), (6.7, 1.05)]:
        assert not grid.is_navigable(x, z)
    assert grid.components()[1] == 1


def test_rotated_box_blocks_its_whole_footprint() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    yaw = 0.6
    c, s = math.cos(yaw), math.sin(yaw)
    rng = np.random.default_rng(0)
    for u, v in rng.uniform(-1.0, 1.0, size=(200, 2)):
        lx, lz = u * 0.45, v * 0.25  # local point of the 0.9 x 0.5 cabinet
        x = 4.5 + c * lx + s * lz
        z = 2.0 - s * lx + c * lz
        assert not grid.is_navigable(x, z)


def test_walls_block_but_the_door_under_its_lintel_connects_the_rooms() -> None:
    grid = NavGrid.from_mesh(scenes.l_shaped_rooms())
    assert grid.components()[1] == 1
    assert grid.is_navigable(1.5, 4.0)  # in the door gap
    assert not grid.is_navigable(0.5, 4.0)  # in the wall beside it
    assert not grid.is_navigable(4.5, 4.0)
    assert grid.component_of(1.5, 2.0) == grid.component_of(1.5, 7.0) != 0


def test_separate_rooms_are_separate_components() -> None:
    grid = NavGrid.from_mesh(scenes.two_separate_rooms())
    labels, count = grid.components()
    assert count == 2
    left, right = grid.component_of(1.5, 1.5), grid.component_of(5.5, 1.5)
    assert {left, right} == {1, 2}
    assert grid.component_of(3.5, 1.5) == 0
    assert grid.largest_component() in (1, 2)
    assert labels.shape == grid.shape


def test_object_taller_than_the_step_blocks_and_lower_one_does_not() -> None:
    room = scenes.closed_room(0.0, 0.0, 4.0, 4.0)
    low = Mesh.concatenate([*room, scenes.box_object(1, 2.0, 2.0, (0.6, 0.1, 0.6))])
    high = Mesh.concatenate([*room, scenes.box_object(1, 2.0, 2.0, (0.6, 0.2, 0.6))])
    assert NavGrid.from_mesh(low, step_height=0.15).is_navigable(2.0, 2.0)
    assert not NavGrid.from_mesh(high, step_height=0.15).is_navigable(2.0, 2.0)


def test_storey_and_parameters_are_validated() -> None:
    mesh = scenes.empty_room()
    with pytest.raises(NavigationError, match="no floor triangles"):
        NavGrid.from_mesh(mesh, floor_y=3.0)
    with pytest.raises(ConfigError, match="agent_radius"):
        NavGrid.from_mesh(mesh, agent_radius=-0.1)
    with pytest.raises(ConfigError, match="cell_size"):
        NavGrid.from_mesh(mesh, cell_size=0.0)
    with pytest.raises(ConfigError, match="step_height"):
        NavGrid.from_mesh(mesh, agent_height=0.1, step_height=0.15)
    grid = NavGrid.from_mesh(mesh, floor_y=0.0, level=2)
    assert (grid.level, grid.floor_y) == (2, 0.0)


def test_cell_and_world_coordinates_round_trip() -> None:
    grid = NavGrid.from_mesh(scenes.l_shaped_rooms())
    rows, cols = grid.shape
    for row, col in [(0, 0), (rows - 1, cols - 1), (rows // 2, cols // 3)]:
        x, z = grid.cell_to_world(row, col)
        assert grid.world_to_cell(x, z) == (row, col)
        assert grid.world_to_cell(x + 0.49 * CELL, z - 0.49 * CELL) == (row, col)
    assert len(grid.free_cells()) == int(grid.navigable.sum())


def test_snap_point_returns_the_nearest_navigable_cell_centre() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    centres = _centres(grid)
    rng = np.random.default_rng(1)
    for x, z in rng.uniform((-1.0, -1.0), (9.0, 7.0), size=(300, 2)):
        sx, sz = grid.snap_point(x, z)
        assert grid.is_navigable(sx, sz)
        row, col = grid.world_to_cell(x, z)
        row = min(max(row, 0), grid.shape[0] - 1)
        col = min(max(col, 0), grid.shape[1] - 1)
        cx, cz = grid.cell_to_world(row, col)
        best = np.min(np.hypot(centres[:, 0] - cx, centres[:, 1] - cz))
        assert math.hypot(sx - cx, sz - cz) == pytest.approx(best, abs=1e-9)
        if grid.is_navigable(x, z):
            assert (sx, sz) == (cx, cz)


def test_snap_point_on_a_grid_without_navigable_cells_fails_clearly() -> None:
    grid = NavGrid(np.zeros((4, 4), bool), (0.0, 0.0), 0.05)
    with pytest.raises(NavigationError, match="no navigable cell"):
        grid.snap_point(0.1, 0.1)


def test_sampling_is_seeded_and_navigable() -> None:
    grid = NavGrid.from_mesh(scenes.two_separate_rooms())
    a = [grid.sample_navigable_point(np.random.default_rng(7)) for _ in range(3)]
    b = [grid.sample_navigable_point(np.random.default_rng(7)) for _ in range(3)]
    assert a == b
    rng = np.random.default_rng(8)
    points = [grid.sample_navigable_point(rng, component=2) for _ in range(50)]
    assert all(grid.component_of(x, z) == 2 for x, z in points)
    with pytest.raises(ConfigError, match="component"):
        grid.sample_navigable_point(rng, component=3)


def test_cast_never_crosses_a_blocked_cell() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    rng = np.random.default_rng(5)
    component = grid.largest_component()
    for _ in range(300):
        x, z = grid.sample_navigable_point(rng, component)
        x += float(rng.uniform(-0.02, 0.02))
        z += float(rng.uniform(-0.02, 0.02))
        angle = float(rng.uniform(-math.pi, math.pi))
        length = float(rng.uniform(0.0, 3.0))
        dx, dz = math.cos(angle) * length, math.sin(angle) * length
        cast = grid.cast(x, z, dx, dz)
        assert grid.is_navigable(cast.x, cast.z)
        # Dense samples up to the stop point lie on navigable cells.
        for t in np.linspace(0.0, cast.fraction, 200)[:-1]:
            assert grid.is_navigable(x + dx * t, z + dz * t)
        if cast.axis >= 0:
            beyond = min(1.0, cast.fraction + 1e-4 / max(length, 1e-9))
            assert not grid.is_navigable(x + dx * beyond, z + dz * beyond)
        else:
            assert cast.fraction == 1.0


def test_cast_from_a_blocked_cell_is_an_error() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room())
    with pytest.raises(NavigationError, match="snap_point"):
        grid.cast(0.0, 0.0, 1.0, 0.0)
