import math

import numpy as np

from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.planner import PathFollower, Planner, turn_toward
from vlln.sim.agent import Action
from vlln.sim.camera import CameraSpec


def _walled_map() -> ObstacleMap:
    """Explored 6 x 6 m around the origin with a wall along z = 1 that has a gap at x 2..3."""
    obstacle_map = ObstacleMap(CameraSpec())
    r0, c0 = obstacle_map.cell_of(-3.0, -3.0)
    r1, c1 = obstacle_map.cell_of(3.0, 3.0)
    obstacle_map.explored[r0:r1, c0:c1] = True
    obstacle_map.mark_free_disc(Pose(0.0, 0.0, 0.0), 3.0)  # grows the explored box
    row, _ = obstacle_map.cell_of(0.0, 1.0)
    wall_end = obstacle_map.cell_of(2.0, 0.0)[1]
    gap_end = obstacle_map.cell_of(3.0, 0.0)[1]
    obstacle_map.obstacle[row, c0:wall_end] = True
    obstacle_map.obstacle[row, gap_end:c1] = True
    return obstacle_map


def test_the_path_goes_through_the_gap_and_keeps_clear_of_the_wall() -> None:
    obstacle_map = _walled_map()
    field = Planner().plan(obstacle_map, Pose(0.0, 0.0, 0.0))
    goal = obstacle_map.cell_of(0.0, 2.5)
    path = np.array(field.path_to(*goal))
    crossing = path[np.argmin(np.abs(path[:, 1] - 1.0))]
    assert 2.0 < crossing[0] < 3.0
    # Through the gap, not the wall: at least the straight lines via the gap's near end.
    assert field.distance(*goal) > math.hypot(2.0, 1.0) + math.hypot(2.0, 1.5)
    row, col = obstacle_map.cell_of(0.0, 1.0)
    assert not np.isfinite(field.distance(row, col))  # wall cells are unreachable


def test_an_obstacle_seen_too_close_does_not_seal_the_agent_in() -> None:
    obstacle_map = ObstacleMap(CameraSpec())
    obstacle_map.mark_free_disc(Pose(0.0, 0.0, 0.0), 3.0)
    # A ring of obstacle cells 0.2 m around the agent, open to the east.
    for angle in np.linspace(0.0, 2.0 * math.pi, 72, endpoint=False):
        if abs(math.cos(angle) - 1.0) > 0.2:
            obstacle_map.obstacle[
                obstacle_map.cell_of(0.2 * math.cos(angle), 0.2 * math.sin(angle))
            ] = True
    field = Planner().plan(obstacle_map, Pose(0.0, 0.0, 0.0))
    assert np.isfinite(field.distance(*obstacle_map.cell_of(2.0, 0.0)))
    path = field.path_to(*obstacle_map.cell_of(2.0, 0.0))
    assert all(not obstacle_map.obstacle[obstacle_map.cell_of(x, z)] for x, z in path)


def test_follower_turns_toward_the_path_then_walks_and_says_when_it_is_there() -> None:
    turn = math.radians(30.0)
    follower = PathFollower([(0.0, 0.0), (1.0, 0.0), (2.0, 0.0)], turn)
    # Yaw 0 looks along -z; the path runs along +x, i.e. to the right.
    assert follower.next_action(Pose(0.0, 0.0, 0.0)) == Action.TURN_RIGHT
    assert follower.next_action(Pose(0.0, 0.0, -math.pi / 2)) == Action.MOVE_FORWARD
    assert follower.next_action(Pose(1.9, 0.0, -math.pi / 2)) is None


def test_turn_toward_leaves_errors_below_half_a_turn() -> None:
    turn = math.radians(30.0)
    assert turn_toward(math.radians(14.0), turn) is None
    assert turn_toward(math.radians(20.0), turn) == Action.TURN_LEFT
    assert turn_toward(math.radians(-20.0), turn) == Action.TURN_RIGHT
