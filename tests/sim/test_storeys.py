"""Houses with two storeys: one navigable structure joined by a flight of stairs."""

from __future__ import annotations

import math
from collections.abc import Iterator
from itertools import pairwise

import numpy as np
import pytest

from vlln.errors import HouseParametersError, NavigationError
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.geodesic import ROUND_UP
from vlln.sim.simulator import Simulator
from vlln.sim.storey_field import StoreyField
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House, ObjectInstance

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)


@pytest.fixture(scope="module")
def house() -> House:
    return generate_house(1, SMALL_TWO_STOREYS)


@pytest.fixture(scope="module")
def sim(house: House) -> Iterator[Simulator]:
    with Simulator(house) as simulator:
        yield simulator


def _stairs(house: House) -> ObjectInstance:
    (flight,) = house.instances_of("stairs")
    return flight


def _point_on(sim: Simulator, level: int, seed: int) -> tuple[float, float, float]:
    storeys = sim.storeys
    assert storeys is not None
    rng = np.random.default_rng(seed)
    main = storeys.largest_component()
    while True:
        point = storeys.sample_navigable_point(rng, main)
        if point[1] == storeys.floor_ys[level]:
            return point


def test_a_two_storey_house_builds_the_same_twice(house: House) -> None:
    again = generate_house(1, SMALL_TWO_STOREYS)
    assert house.geometry is not None and again.geometry is not None
    assert house.geometry.mesh.positions.tobytes() == again.geometry.mesh.positions.tobytes()
    assert house.instances == again.instances
    assert sorted({(room.level, room.floor_y) for room in house.rooms}) == [(0, 0.0), (1, 2.8)]
    flight = _stairs(house)
    assert flight.box.min[1] == 0.0 and flight.box.max[1] == pytest.approx(2.8)
    assert [inst.id for inst in house.instances] == list(range(1, len(house.instances) + 1))


def test_floors_outside_one_to_three_are_refused() -> None:
    with pytest.raises(HouseParametersError, match="floors"):
        HouseParameters(floors=4).validate()


def test_one_walkable_structure_spans_both_storeys(sim: Simulator) -> None:
    storeys = sim.storeys
    assert storeys is not None
    labels, _ = storeys.components()
    main = labels == storeys.largest_component()
    cells = storeys.shape[0] * storeys.shape[1]
    assert main[:cells].sum() > 1000 and main[cells:].sum() > 1000
    with pytest.raises(NavigationError, match="storeys"):
        _ = sim.grid


def test_the_geodesic_climbs_the_stairs_and_beats_no_straight_line(
    sim: Simulator, house: House
) -> None:
    flight = _stairs(house).box
    for seed in range(3):
        below, above = _point_on(sim, 0, seed), _point_on(sim, 1, seed)
        field = sim.distance_field([above])
        assert isinstance(field, StoreyField)
        distance = field.distance(below[0], below[2], below[1])
        assert math.isfinite(distance)
        assert distance >= math.dist(below, above)
        path = field.path_nodes(*below)
        on_flight = [
            p
            for p in path
            if flight.min[0] <= p[0] <= flight.max[0] and flight.min[2] <= p[2] <= flight.max[2]
        ]
        heights = [p[1] for p in on_flight]
        assert min(heights) < 0.5 and max(heights) > 2.3  # the whole flight, step by step
        # Every other point of the path is on a floor.
        assert {round(p[1], 6) for p in path if p not in on_flight} <= {0.0, 2.8}
        with pytest.raises(NavigationError, match="height"):
            field.distance(below[0], below[2])


@pytest.mark.parametrize("start_level", [0, 1])
def test_the_follower_walks_up_and_down_the_stairs(sim: Simulator, start_level: int) -> None:
    start = _point_on(sim, start_level, 7)
    goal = _point_on(sim, 1 - start_level, 8)
    field = sim.distance_field([goal])
    follower = GreedyFollower(sim.nav, field, 0.25, sim.config.motion)
    sim.reset(AgentState(start, 0.0, 0.0))
    heights = []
    for _ in range(1000):
        action = follower.next_action(sim.state)
        if action == Action.STOP:
            break
        sim.move(action)
        heights.append(sim.state.position[1])
    x, y, z = sim.state.position
    assert field.distance(x, z, y) < 0.25
    assert y == pytest.approx(goal[1])
    assert len({round(h, 3) for h in heights}) > 10  # it passed the steps one by one
    assert all(abs(b - a) < 0.45 for a, b in pairwise(heights))


def test_a_bounded_storey_field_is_the_whole_field_within_its_limit(sim: Simulator) -> None:
    goal = _point_on(sim, 1, 0)
    limit = 2.0
    whole_field, bounded_field = sim.distance_field([goal]), sim.distance_field([goal], limit=limit)
    assert isinstance(whole_field, StoreyField) and isinstance(bounded_field, StoreyField)
    whole, bounded = np.concatenate(whole_field.values), np.concatenate(bounded_field.values)
    inside = whole <= limit
    beyond = whole > limit * ROUND_UP
    assert inside.sum() > 100 and (beyond & np.isfinite(whole)).sum() > 100
    np.testing.assert_array_equal(bounded[inside], whole[inside])
    assert np.isinf(bounded[beyond]).all()
