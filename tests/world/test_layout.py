"""Tests of floor plans: room counts, areas, room types, doors and reachability."""

from __future__ import annotations

from collections import deque

import numpy as np
import pytest

from vlln.world.generator.doors import DEAD_END_ROOMS, shared_walls
from vlln.world.generator.layout import CORRIDOR_MIN_ROOMS, FloorPlan, plan_floor
from vlln.world.generator.params import DOOR_CORNER_MARGIN, MIN_ROOM_SIDE, HouseParameters
from vlln.world.generator.rect import Rect
from vlln.world.model import Door, Room

PARAMETER_SETS = [
    HouseParameters(),
    HouseParameters(min_rooms=2, max_rooms=5, min_area=30.0, max_area=70.0),
    HouseParameters(min_rooms=12, max_rooms=12, min_area=60.0, max_area=90.0, door_width=1.0),
    HouseParameters(min_rooms=15, max_rooms=20, min_area=300.0, max_area=400.0),
]


def plans(params: HouseParameters, n: int = 12) -> list[FloorPlan]:
    return [plan_floor(params, np.random.default_rng(seed)) for seed in range(n)]


def reachable_rooms(rooms: list[Room], doors: list[Door]) -> set[int]:
    neighbours: dict[int, set[int]] = {room.id: set() for room in rooms}
    for door in doors:
        neighbours[door.room_a].add(door.room_b)
        neighbours[door.room_b].add(door.room_a)
    seen = {rooms[0].id}
    queue = deque(seen)
    while queue:
        for nxt in neighbours[queue.popleft()] - seen:
            seen.add(nxt)
            queue.append(nxt)
    return seen


@pytest.mark.parametrize("params", PARAMETER_SETS)
def test_room_count_and_floor_area_follow_the_parameters(params: HouseParameters) -> None:
    for plan in plans(params):
        assert params.min_rooms <= len(plan.rooms) <= params.max_rooms
        assert params.min_area - 1e-6 <= plan.area <= params.max_area + 1e-6
        for room in plan.rooms:
            assert room.ceiling_height == params.ceiling_height
            assert room.floor_y == 0.0


@pytest.mark.parametrize("params", PARAMETER_SETS)
def test_rooms_are_disjoint_and_not_too_narrow(params: HouseParameters) -> None:
    for plan in plans(params):
        rects = plan.rects
        for rect in rects:
            assert min(rect.width, rect.depth) >= MIN_ROOM_SIDE - 1e-6
        for i, a in enumerate(rects):
            for b in rects[i + 1 :]:
                overlap_x = min(a.x1, b.x1) - max(a.x0, b.x0)
                overlap_z = min(a.z1, b.z1) - max(a.z0, b.z0)
                assert overlap_x <= 1e-9 or overlap_z <= 1e-9


@pytest.mark.parametrize("params", PARAMETER_SETS)
def test_every_room_is_reachable_through_doors(params: HouseParameters) -> None:
    for plan in plans(params):
        assert reachable_rooms(plan.rooms, plan.doors) == {room.id for room in plan.rooms}


@pytest.mark.parametrize("params", PARAMETER_SETS)
def test_doors_sit_on_shared_walls_away_from_corners(params: HouseParameters) -> None:
    for plan in plans(params):
        walls = {(w.room_a, w.room_b): w for w in shared_walls(plan.rects)}
        for door in plan.doors:
            assert door.width == params.door_width
            wall = walls[(door.room_a, door.room_b)]
            assert door.axis == wall.axis
            along, across = door.center if door.axis == "x" else door.center[::-1]
            assert across == wall.coord
            margin = DOOR_CORNER_MARGIN + params.wall_thickness / 2.0
            assert along - door.width / 2.0 >= wall.start + margin - 1e-9
            assert along + door.width / 2.0 <= wall.end - margin + 1e-9


def test_room_types_are_realistic() -> None:
    for plan in plans(HouseParameters(), n=40):
        types = [room.type for room in plan.rooms]
        areas = {room.id: Rect.of_room(room).area for room in plan.rooms}
        assert {"living room", "kitchen", "bathroom"} <= set(types)
        assert ("corridor" in types) == (len(types) >= CORRIDOR_MIN_ROOMS)
        living = max(areas[r.id] for r in plan.rooms if r.type == "living room")
        for room in plan.rooms:
            if room.type in DEAD_END_ROOMS:
                assert areas[room.id] < living


def test_bathrooms_toilets_and_storage_rooms_are_dead_ends() -> None:
    for plan in plans(HouseParameters(), n=40):
        for room in plan.rooms:
            if room.type in DEAD_END_ROOMS:
                doors = [d for d in plan.doors if room.id in (d.room_a, d.room_b)]
                assert len(doors) == 1, (room, doors)


def test_same_generator_state_gives_the_same_plan() -> None:
    a = plan_floor(HouseParameters(), np.random.default_rng(7))
    b = plan_floor(HouseParameters(), np.random.default_rng(7))
    c = plan_floor(HouseParameters(), np.random.default_rng(8))
    assert a.rooms == b.rooms and a.doors == b.doors
    assert a.rooms != c.rooms
