"""The collector's stairs: where and when a flight is taken, and walks up and down it."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from vlln.agents.frontier.mapping import MapConfig, Pose
from vlln.datagen.collector.lattice import plan_walk
from vlln.datagen.collector.stairs import Flight, FlightChoices, house_flights
from vlln.datagen.collector.storey_maps import StoreyMaps
from vlln.sim.agent import AgentState, step
from vlln.sim.camera import CameraSpec
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.splits import house_seeds


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    cache = SceneCache(capacity=1)
    yield cache.get(procedural_scene_id(house_seeds("train", 1)[0], 2))
    cache.close()


@pytest.mark.slow
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


@pytest.mark.slow
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


def test_flights_are_offered_once_seen_toward_the_target_or_once_a_storey_is_done() -> None:
    flight = Flight(7, 0, 1, foot=(2.0, 0.0, 0.0), head=(-2.0, 2.8, 0.0))
    upstairs = FlightChoices([flight], 0, lambda p: 10.0 - p[1])  # the target is upstairs
    maps = StoreyMaps(CameraSpec(), MapConfig(cell_size=0.05), origin=(0.0, 0.0))
    below = AgentState((0.0, 0.0, 0.0), 0.0)
    maps.of(0, below)  # its landing not yet seen
    upstairs.note(0, maps)
    assert upstairs.toward_target(0) is None
    assert upstairs.options(0, exhausted=False) == []
    assert upstairs.options(0, exhausted=True) == [flight]
    maps.of(0, below).mark_free_disc(Pose(2.0, 0.0, 0.0), 0.3)  # now it is
    upstairs.note(0, maps)
    assert upstairs.toward_target(0) is flight
    upstairs.took(flight, 0)
    upstairs.took(flight, 0)
    assert upstairs.toward_target(0) is None  # taken twice from this storey: enough
    downstairs = FlightChoices([flight], 0, lambda p: p[1])
    downstairs.note(0, maps)
    assert downstairs.toward_target(0) is None  # it leads away from the target
    assert downstairs.nearer_end(0) == (flight, flight.foot)
    assert downstairs.first_visit(1) and not downstairs.first_visit(1)
    assert not downstairs.first_visit(0)  # the start's storey
