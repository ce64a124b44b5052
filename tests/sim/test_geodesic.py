from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from tests.sim import scenes
from vlln.errors import NavigationError
from vlln.sim.geodesic import ROUND_UP, GeodesicField
from vlln.sim.navgrid import NavGrid


@pytest.fixture(scope="module")
def furnished() -> NavGrid:
    return NavGrid.from_mesh(scenes.furnished_room())


@pytest.fixture(scope="module")
def l_rooms() -> NavGrid:
    return NavGrid.from_mesh(scenes.l_shaped_rooms())


def _jitter(rng: np.random.Generator, point: tuple[float, float]) -> tuple[float, float]:
    """A random point inside the same 5 cm cell."""
    return point[0] + float(rng.uniform(-0.0249, 0.0249)), point[1] + float(
        rng.uniform(-0.0249, 0.0249)
    )


def _polyline_length(points: list[tuple[float, float]]) -> float:
    return sum(math.dist(a, b) for a, b in itertools.pairwise(points))


@pytest.mark.parametrize("scene", ["furnished_room", "l_shaped_rooms", "divided_room"])
def test_geodesic_is_never_shorter_than_the_straight_line(scene: str) -> None:
    grid = NavGrid.from_mesh(getattr(scenes, scene)())
    rng = np.random.default_rng(11)
    component = grid.largest_component()
    for _ in range(8):
        goal = _jitter(rng, grid.sample_navigable_point(rng, component))
        field = GeodesicField(grid, [goal])
        (snapped,) = field.goals
        assert field.distance(*snapped) == 0.0
        for _ in range(100):
            x, z = _jitter(rng, grid.sample_navigable_point(rng, component))
            d = field.distance(x, z)
            assert math.isfinite(d)
            assert d >= math.dist((x, z), snapped)


def test_geodesic_in_an_empty_room_is_close_to_the_straight_line() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))
    rng = np.random.default_rng(2)
    for _ in range(10):
        goal = grid.sample_navigable_point(rng)
        field = GeodesicField(grid, [goal])
        for _ in range(50):
            point = grid.sample_navigable_point(rng)
            straight = math.dist(point, goal)
            assert straight <= field.distance(*point) <= straight * 1.03 + 1e-9


def test_detour_around_a_wall_has_the_expected_length() -> None:
    grid = NavGrid.from_mesh(scenes.divided_room())
    field = GeodesicField(grid, [(4.5, 1.0)])
    start = (1.5, 1.0)
    d = field.distance(*start)
    # The wall x = 3 (0.1 m thick) runs from z = 0 to z = 5.05; any path passes its end.
    lower = 2 * math.hypot(1.5 - 0.05, 5.05 - 1.0)
    # Going through (3.0, 5.4), a point with clearance, is one valid path.
    upper = 2 * math.hypot(1.5, 5.4 - 1.0)
    assert lower < d < upper * 1.02
    path = field.shortest_path(*start)
    assert path[0] == start
    assert path[-1] == field.goals[0]
    assert max(z for _, z in path) > 5.05
    assert _polyline_length(path) <= d + 1e-9
    assert _polyline_length(path) > lower


def test_shortest_path_stays_on_the_navigable_area(furnished: NavGrid) -> None:
    rng = np.random.default_rng(4)
    component = furnished.largest_component()
    for _ in range(30):
        goal = furnished.sample_navigable_point(rng, component)
        field = GeodesicField(furnished, [goal])
        start = _jitter(rng, furnished.sample_navigable_point(rng, component))
        path = field.shortest_path(*start)
        assert path[0] == start and path[-1] == goal
        for (x0, z0), (x1, z1) in itertools.pairwise(path):
            assert furnished.segment_is_clear(x0, z0, x1, z1)
        length = _polyline_length(path)
        assert math.dist(start, goal) - 1e-9 <= length <= field.distance(*start) + 1e-9


def test_string_pulling_makes_a_straight_path_in_open_space() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))
    field = GeodesicField(grid, [(5.0, 3.0)])
    assert field.shortest_path(1.0, 1.5) == [(1.0, 1.5), field.goals[0]]


def test_several_goals_give_the_distance_to_the_nearest(l_rooms: NavGrid) -> None:
    goals = [(1.0, 1.0), (5.0, 3.0), (1.5, 8.0)]
    both = GeodesicField(l_rooms, goals)
    singles = [GeodesicField(l_rooms, [g]) for g in goals]
    rng = np.random.default_rng(6)
    for _ in range(200):
        x, z = _jitter(rng, l_rooms.sample_navigable_point(rng))
        expected = min(f.distance(x, z) for f in singles)
        assert both.distance(x, z) == pytest.approx(expected, rel=1e-12)


def test_the_door_is_the_only_way_between_the_rooms(l_rooms: NavGrid) -> None:
    field = GeodesicField(l_rooms, [(1.5, 8.0)])
    start = (5.0, 1.0)
    # The path must pass the door gap, x in [1, 2] at z = 4.
    via_door = math.dist(start, (2.0 - 0.2, 4.0)) + math.dist((2.0 - 0.2, 4.0), (1.5, 8.0))
    assert field.distance(*start) == pytest.approx(via_door, rel=0.05)
    path = field.shortest_path(*start)
    crossing = [
        (x0 + (x1 - x0) * (4.0 - z0) / (z1 - z0))
        for (x0, z0), (x1, z1) in itertools.pairwise(path)
        if (z0 - 4.0) * (z1 - 4.0) < 0
    ]
    assert len(crossing) == 1 and 1.0 < crossing[0] < 2.0


def test_unreachable_and_off_grid_points_are_infinitely_far() -> None:
    grid = NavGrid.from_mesh(scenes.two_separate_rooms())
    field = GeodesicField(grid, [(1.5, 1.5)])
    assert field.distance(1.0, 1.0) < math.inf
    assert field.distance(5.5, 1.5) == math.inf
    assert not field.is_reachable(5.5, 1.5)
    assert field.distance(-50.0, 1.0) == math.inf
    assert np.isinf(field.values[grid.world_to_cell(5.5, 1.5)])
    with pytest.raises(NavigationError, match="no path"):
        field.shortest_path(5.5, 1.5)


def test_goals_are_snapped_and_off_grid_goals_ignored(furnished: NavGrid) -> None:
    field = GeodesicField(furnished, [(2.0, 2.0), (100.0, 100.0)])  # table centre, far away
    (goal,) = field.goals
    assert furnished.is_navigable(*goal)
    assert field.distance(*goal) == 0.0


def test_bad_goal_sets_are_rejected(furnished: NavGrid) -> None:
    with pytest.raises(NavigationError, match="empty"):
        GeodesicField(furnished, [])
    with pytest.raises(NavigationError, match="none of the 2 goals"):
        GeodesicField(furnished, [(100.0, 0.0), (0.0, -100.0)])


def test_cell_graph_joins_only_navigable_cells_with_euclidean_weights(l_rooms: NavGrid) -> None:
    graph = l_rooms.cell_graph()
    assert graph is l_rooms.cell_graph()  # built once
    assert (graph != graph.T).nnz == 0
    coo = graph.tocoo()
    cols = l_rooms.shape[1]
    navigable = l_rooms.navigable.ravel()
    assert navigable[coo.row].all() and navigable[coo.col].all()
    dr = coo.row // cols - coo.col // cols
    dc = coo.row % cols - coo.col % cols
    assert np.allclose(coo.data, l_rooms.cell_size * np.hypot(dr, dc))
    assert set(zip(np.abs(dr).tolist(), np.abs(dc).tolist(), strict=True)) == {
        (0, 1),
        (1, 0),
        (1, 1),
        (1, 2),
        (2, 1),
    }


@pytest.mark.parametrize("scene", ["furnished_room", "l_shaped_rooms", "divided_room"])
def test_a_bounded_field_is_the_whole_field_within_its_limit_and_inf_beyond(scene: str) -> None:
    grid = NavGrid.from_mesh(getattr(scenes, scene)())
    rng = np.random.default_rng(5)
    component = grid.largest_component()
    limit = 1.5
    for _ in range(4):
        goal = grid.sample_navigable_point(rng, component)
        whole = GeodesicField(grid, [goal])
        bounded = GeodesicField(grid, [goal], limit)
        inside = whole.values <= limit
        beyond = whole.values > limit * ROUND_UP  # rounding up keeps a thin band undecided
        assert inside.sum() > 100 and (beyond & np.isfinite(whole.values)).sum() > 100
        np.testing.assert_array_equal(bounded.values[inside], whole.values[inside])
        assert np.isinf(bounded.values[beyond]).all()
        for _ in range(50):
            x, z = _jitter(rng, grid.sample_navigable_point(rng, component))
            d = whole.distance(x, z)
            if d <= limit:
                assert bounded.distance(x, z) == d
            elif d > limit * ROUND_UP + grid.cell_size:  # its cell is beyond the limit too
                assert bounded.distance(x, z) == math.inf
