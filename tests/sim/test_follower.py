from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from tests.sim import scenes
from vlln.errors import ConfigError, NavigationError
from vlln.sim.agent import Action, AgentState, MotionConfig, step
from vlln.sim.follower import ForwardProbes, GreedyFollower
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid

MOTION = MotionConfig()
TURNS = {Action.TURN_LEFT, Action.TURN_RIGHT}


def _follow(
    grid: NavGrid, field: GeodesicField, state: AgentState, limit: int
) -> tuple[AgentState, list[Action], int]:
    """Run the follower until STOP or ``limit`` actions; also count collisions."""
    follower = GreedyFollower(grid, field)
    actions: list[Action] = []
    collisions = 0
    while len(actions) < limit:
        action = follower.next_action(state)
        actions.append(action)
        if action == Action.STOP:
            break
        result = step(state, action, grid, MOTION)
        state = result.state
        collisions += result.collided
    return state, actions, collisions


@pytest.mark.parametrize(
    "scene", ["l_shaped_rooms", "divided_room", "furnished_room", "empty_room"]
)
def test_the_follower_reaches_every_sampled_goal(scene: str) -> None:
    grid = NavGrid.from_mesh(getattr(scenes, scene)())
    rng = np.random.default_rng(31)
    component = grid.largest_component()
    for _ in range(25):
        goal = grid.sample_navigable_point(rng, component)
        field = GeodesicField(grid, [goal])
        x, z = grid.sample_navigable_point(rng, component)
        start = AgentState((x, 0.0, z), float(rng.uniform(-math.pi, math.pi)))
        d0 = field.distance(x, z)
        # Forward steps for the distance, turns to face each way, and slack for corners.
        limit = int(2.0 * d0 / MOTION.forward_step) + 40
        final, actions, collisions = _follow(grid, field, start, limit)
        assert actions[-1] == Action.STOP, f"no STOP within {limit} actions from {(x, z)}"
        fx, _, fz = final.position
        assert field.distance(fx, fz) < 0.25
        # Close to the shortest path: forward steps cover little more than the distance.
        forward = actions.count(Action.MOVE_FORWARD) * MOTION.forward_step
        assert forward <= 1.1 * d0 + MOTION.forward_step
        # Never turns back and forth, never spins more than half a turn in one go.
        for a, b in itertools.pairwise(actions):
            assert {a, b} != TURNS
        run = 0
        for action in actions:
            run = run + 1 if action in TURNS else 0
            assert run <= 6
        # Passages here are wide enough for collision-free expert trajectories.
        assert collisions == 0


def test_the_follower_stops_at_the_goal_and_is_deterministic() -> None:
    grid = NavGrid.from_mesh(scenes.l_shaped_rooms())
    field = GeodesicField(grid, [(1.5, 8.0)])
    follower = GreedyFollower(grid, field)
    (goal,) = field.goals
    assert follower.next_action(AgentState((goal[0], 0.0, goal[1]), 1.0)) == Action.STOP
    start = AgentState((5.0, 0.0, 1.0), 0.3)
    first = _follow(grid, field, start, 400)
    second = _follow(grid, field, start, 400)
    assert first == second
    assert first[1][-1] == Action.STOP


def test_the_follower_turns_toward_a_goal_behind_it() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))
    field = GeodesicField(grid, [(1.0, 2.0)])  # west of the agent
    follower = GreedyFollower(grid, field)
    facing_north = AgentState((5.0, 0.0, 2.0), 0.0)  # looks along -z
    assert follower.next_action(facing_north) == Action.TURN_LEFT  # west is to its left
    facing_west = AgentState((5.0, 0.0, 2.0), math.pi / 2)
    assert follower.next_action(facing_west) == Action.MOVE_FORWARD
    facing_south = AgentState((5.0, 0.0, 2.0), math.pi)
    assert follower.next_action(facing_south) == Action.TURN_RIGHT


def test_ties_between_left_and_right_go_left() -> None:
    grid = NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))
    field = GeodesicField(grid, [(3.025, 3.025)])  # straight behind an agent looking along -z
    motion = MotionConfig(turn_deg=40.0)  # no heading points straight back: +-160 tie
    follower = GreedyFollower(grid, field, motion=motion)
    assert follower.next_action(AgentState((3.025, 0.0, 1.025), 0.0)) == Action.TURN_LEFT


def test_bad_follower_settings_and_unreachable_goals_are_errors() -> None:
    grid = NavGrid.from_mesh(scenes.two_separate_rooms())
    field = GeodesicField(grid, [(1.5, 1.5)])
    with pytest.raises(ConfigError, match="goal_radius"):
        GreedyFollower(grid, field, goal_radius=-0.25)
    other = NavGrid.from_mesh(scenes.empty_room())
    with pytest.raises(ConfigError, match="different grid"):
        GreedyFollower(other, field)
    follower = GreedyFollower(grid, field)
    with pytest.raises(NavigationError, match="no goal can be reached"):
        follower.next_action(AgentState((5.5, 0.0, 1.5)))


def test_followers_sharing_forward_probes_choose_as_they_would_alone() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    rng = np.random.default_rng(5)
    component = grid.largest_component()
    probes = ForwardProbes(grid, MOTION)
    states = []
    for _ in range(20):
        x, z = grid.sample_navigable_point(rng, component)
        states.append(AgentState((x, 0.0, z), float(rng.uniform(-math.pi, math.pi))))
    for _ in range(4):  # four goals asked about the same places
        field = GeodesicField(grid, [grid.sample_navigable_point(rng, component)])
        alone, shared = GreedyFollower(grid, field), GreedyFollower(grid, field, probes=probes)
        for state in states:
            assert shared.next_action(state) == alone.next_action(state)
    assert probes.around(states[0]) is probes.around(states[0])  # made once
    with pytest.raises(ConfigError, match="another grid or motion"):
        GreedyFollower(grid, field, motion=MotionConfig(turn_deg=45.0), probes=probes)
