"""The collector's stairs: where a flight is taken, and collision-free walks up and down it."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from vlln.datagen.collector.lattice import plan_walk
from vlln.datagen.collector.stairs import house_flights
from vlln.sim.agent import AgentState, step
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.splits import house_seeds


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    cache = SceneCache(capacity=1)
    yield cache.get(procedural_scene_id(house_seeds("train", 1)[0], 2))
    cache.close()


def test_a_flight_joins_a_landing_below_to_one_above(sim: Simulator) -> None:
    storeys = sim.storeys
    assert storeys is not None
    (flight,) = house_flights(sim.house, storeys)
    assert (flight.lower, flight.upper) == (0, 1)
    assert flight.foot[1] == storeys.floor_ys[0] and flight.head[1] == storeys.floor_ys[1]
    assert storeys.is_navigable(*flight.foot) and storeys.is_navigable(*flight.head)
    assert flight.end_on(0) == flight.arrival(1) == flight.foot
    assert flight.end_on(1) == flight.arrival(0) == flight.head
    # The way between the landings is the flight: its slope (3.6 m run, one storey's rise)
    # and a little of each landing.
    x, y, z = flight.foot
    walk = sim.distance_field([flight.head]).distance(x, z, y)
    rise = storeys.floor_ys[1] - storeys.floor_ys[0]
    assert (3.6**2 + rise**2) ** 0.5 < walk < (3.6**2 + rise**2) ** 0.5 + 2.0


@pytest.mark.parametrize("upward", [True, False])
def test_a_planned_walk_takes_the_stairs_without_colliding(sim: Simulator, upward: bool) -> None:
    storeys = sim.storeys
    assert storeys is not None
    (flight,) = house_flights(sim.house, storeys)
    start, goal = (flight.foot, flight.head) if upward else (flight.head, flight.foot)
    field = sim.distance_field([goal])
    motion = sim.config.motion
    state = AgentState(start, 1.0)
    plan = plan_walk(storeys, field, motion, state, 0.25, max_expansions=30000)
    assert plan is not None
    heights = [state.position[1]]
    for action in plan:
        result = step(state, action, storeys, motion)
        assert not result.collided
        state = result.state
        heights.append(state.position[1])
    x, y, z = state.position
    assert field.distance(x, z, y) < 0.25
    assert y == goal[1]
    ordered = heights if upward else heights[::-1]
    assert ordered == sorted(ordered)  # the height follows the treads, one way
