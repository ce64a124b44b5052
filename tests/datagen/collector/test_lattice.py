"""Collision-free walks on the motion lattice."""

from __future__ import annotations

import numpy as np
import pytest

from vlln.datagen.collector.lattice import LatticeFollower, plan_walk
from vlln.sim.agent import Action, AgentState, step
from vlln.tasks.scenes import SceneCache, procedural_scene_id


@pytest.mark.slow
def test_planned_walks_reach_the_goal_without_colliding() -> None:
    cache = SceneCache(capacity=1)
    sim = cache.get(procedural_scene_id(2))
    grid, motion = sim.grid, sim.config.motion
    rng = np.random.default_rng(0)
    component = grid.largest_component()
    found = 0
    for _ in range(12):
        start_xz = grid.sample_navigable_point(rng, component)
        goal = grid.sample_navigable_point(rng, component)
        field = sim.geodesic_field([goal])
        state = AgentState((start_xz[0], 0.0, start_xz[1]), float(rng.uniform(-np.pi, np.pi)))
        plan = plan_walk(grid, field, motion, state, 0.25, max_expansions=30000)
        if plan is None:
            continue
        found += 1
        for action in plan:
            result = step(state, action, grid, motion)
            assert not result.collided
            state = result.state
        assert field.distance(state.position[0], state.position[2]) < 0.25
        assert len(plan) >= field.distance(start_xz[0], start_xz[1]) / motion.forward_step - 1
    assert found >= 10
    cache.close()


def test_follower_stops_at_the_goal_and_checks_each_step() -> None:
    cache = SceneCache(capacity=1)
    sim = cache.get(procedural_scene_id(2))
    grid, motion = sim.grid, sim.config.motion
    rng = np.random.default_rng(1)
    component = grid.largest_component()
    start = grid.sample_navigable_point(rng, component)
    goal = grid.sample_navigable_point(rng, component)
    follower = LatticeFollower(grid, sim.geodesic_field([goal]), 0.25, motion, 30000)
    state = AgentState((start[0], 0.0, start[1]), 0.3)
    for _ in range(2000):
        action = follower.next_action(state)
        assert action is not None
        if action == Action.STOP:
            break
        result = step(state, action, grid, motion)
        assert not result.collided
        state = result.state
    assert action == Action.STOP
    assert follower.field.distance(state.position[0], state.position[2]) < 0.25
    cache.close()
