import math

import numpy as np

from vlln.agents.frontier.frontiers import ChooserConfig, choose_frontier, find_frontiers


def _half_explored_room() -> tuple[np.ndarray, np.ndarray]:
    """20x20 cells; columns 0..9 explored; rows 0 and 19 are walls."""
    explored = np.zeros((20, 20), bool)
    explored[:, :10] = True
    free = explored.copy()
    free[0, :] = free[19, :] = False
    return free, explored


def test_one_frontier_on_the_boundary_with_its_middle_cell() -> None:
    free, explored = _half_explored_room()
    frontiers = find_frontiers(free, explored, min_cells=3, min_pocket_cells=10)
    assert len(frontiers) == 1
    frontier = frontiers[0]
    assert frontier.col == 9  # the last explored column, next to the unexplored
    assert frontier.size == 18
    assert 9 <= frontier.row <= 10


def test_small_unexplored_pockets_and_short_runs_are_ignored() -> None:
    explored = np.ones((30, 30), bool)
    explored[10:13, 10:13] = False  # a 9-cell pocket inside explored free space
    free = explored.copy()
    assert find_frontiers(free, explored, min_cells=3, min_pocket_cells=150) == []
    pocket = find_frontiers(free, explored, min_cells=3, min_pocket_cells=5)
    assert len(pocket) == 1 and pocket[0].size == 12
    assert find_frontiers(free, explored, min_cells=13, min_pocket_cells=5) == []


def test_unexplored_at_the_window_border_is_never_a_pocket() -> None:
    free, explored = _half_explored_room()
    explored[:, 10:] = True
    explored[5:8, 19] = False  # tiny, but it touches the border
    free = explored.copy()
    frontiers = find_frontiers(free, explored, min_cells=1, min_pocket_cells=1000)
    assert [(f.row, f.col) for f in frontiers] == [(6, 18)]


def test_obstacles_between_explored_and_unexplored_make_no_frontier() -> None:
    free, explored = _half_explored_room()
    free[:, 9] = False  # a wall along the boundary
    assert find_frontiers(free, explored, min_cells=1, min_pocket_cells=1) == []


def test_choice_rules() -> None:
    points = np.array([[0.0, -5.0], [5.0, 0.0], [-3.0, 0.0], [0.0, 2.0]])
    distances = np.array([5.0, 5.0, 3.0, np.inf])  # the last one cannot be reached
    rng = np.random.default_rng(0)
    agent = (0.0, 0.0)
    config = ChooserConfig()
    # First choice: the nearest reachable one.
    assert choose_frontier(points, distances, agent, None, None, rng, config) == 2
    # A hint (yaw 0 looks along -z) overrides: the frontier straight ahead.
    assert choose_frontier(points, distances, agent, None, 0.0, rng, config) == 0
    # Hint to the right (negative yaw): the frontier at +x.
    assert choose_frontier(points, distances, agent, None, -math.pi / 2, rng, config) == 1
    # Continue near the previous choice, or go to the nearest to the agent.
    always = ChooserConfig(p_continue=1.0)
    never = ChooserConfig(p_continue=0.0)
    assert choose_frontier(points, distances, agent, (4.0, 1.0), None, rng, always) == 1
    assert choose_frontier(points, distances, agent, (4.0, 1.0), None, rng, never) == 2
    unreachable = np.full(4, np.inf)
    assert choose_frontier(points, unreachable, agent, None, None, rng, config) is None
