"""Random walks through a house and the step rate along them: what ``vlln bench sim`` and its
multi-process variant both time (one module, so neither borrows the other's helpers)."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from vlln.sim.agent import Action, AgentState
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import GoalPoint

# Forward-biased random walk: how an exploring agent moves.
WALK = (Action.MOVE_FORWARD, Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT)


@dataclass(frozen=True)
class Walk:
    """A random walk: where it starts, the actions taken and the pose after each."""

    start: AgentState
    actions: list[Action]
    poses: list[AgentState]


def random_walk(sim: Simulator, rng: np.random.Generator, count: int) -> Walk:
    """A forward-biased random walk through the house: the views an agent would really see.
    Every figure that renders replays this walk, so they all draw the same frames."""
    start = AgentState(random_point(sim, rng), float(rng.uniform(-math.pi, math.pi)), 0.0)
    sim.reset(start)
    actions = [WALK[int(i)] for i in rng.integers(len(WALK), size=count)]
    poses = []
    for action in actions:
        sim.move(action)
        poses.append(sim.state)
    return Walk(start, actions, poses)


def random_point(sim: Simulator, rng: np.random.Generator) -> tuple[float, float, float]:
    """A navigable ``(x, y, z)`` of the main walkable structure, on any storey."""
    if sim.storeys is not None:
        return sim.storeys.sample_navigable_point(rng, sim.storeys.largest_component())
    x, z = sim.grid.sample_navigable_point(rng, sim.grid.largest_component())
    return x, sim.grid.floor_y, z


def goal_sets(sim: Simulator, rng: np.random.Generator, count: int) -> list[list[GoalPoint]]:
    """View points of randomly chosen objects: the goal sets a task builds fields for
    (``(x, y, z)`` in a house with several storeys)."""
    sets: list[list[GoalPoint]] = []
    for index in rng.permutation(len(sim.house.instances)):
        points = sim.view_points(sim.house.instances[int(index)].box)
        if points:
            sets.append(points)
        if len(sets) == count:
            break
    return sets


def step_fps(sim: Simulator, walk: Walk, goals: list[GoalPoint]) -> float:
    """Action + collision + render + a geodesic query, as a task does every step."""
    field = sim.distance_field(goals)
    sim.reset(walk.start)
    start = time.perf_counter()
    for action in walk.actions:
        observation = sim.step(action)
        x, y, z = observation.state.position
        field.distance(x, z, y)
    return len(walk.actions) / (time.perf_counter() - start)
