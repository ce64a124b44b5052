"""The house index finds the objects a question names, and no object in its grammar, and the
room of a point on the storey asked about."""

import numpy as np
import pytest
from matplotlib.path import Path

from vlln.oracle.knowledge import HouseIndex
from vlln.world.generator import HouseParameters, generate_house


@pytest.mark.slow
def test_the_auxiliary_can_is_not_the_object_can() -> None:
    house = next(h for h in map(generate_house, range(20)) if h.instances_of("can"))
    pattern = HouseIndex.build(house).category_pattern
    named = [m.group(1) for m in pattern.finditer("can it be found next to the can?")]
    assert named == ["can"]
    question = "can you see it by the cans"
    assert [m.start() for m in pattern.finditer(question)] == [question.index("cans")]
    assert not list(pattern.finditer("can i find it there? can we go?"))


def test_rooms_at_agrees_with_matplotlib_on_every_storey() -> None:
    house = generate_house(3, HouseParameters(floors=3))
    index = HouseIndex.build(house)
    rng = np.random.default_rng(0)
    corners = np.array([p for room in house.rooms for p in room.polygon], np.float64)
    low, high = corners.min(axis=0) - 1.0, corners.max(axis=0) + 1.0
    points = rng.uniform(low, high, size=(2000, 2))
    levels = sorted({room.level for room in house.rooms})
    assert len(levels) == 3
    for level in levels:
        rooms = [room for room in house.rooms if room.level == level]
        expected = np.full(len(points), -1)
        for room in reversed(rooms):  # the first room that holds a point names it
            expected[Path(np.asarray(room.polygon)).contains_points(points)] = room.id
        found = index.rooms_at(points, rooms[0].floor_y)
        assert (found == expected).all()
        assert 0.2 < (found >= 0).mean() < 1.0  # points both inside and outside rooms


def test_a_point_just_outside_the_house_belongs_to_the_room_whose_wall_it_faces() -> None:
    house = generate_house(3, HouseParameters(floors=3))
    index = HouseIndex.build(house)
    outer_x_of_storey: dict[int, float] = {}
    for room in house.rooms:
        x = max(p[0] for p in room.polygon)
        outer_x_of_storey[room.level] = max(x, outer_x_of_storey.get(room.level, x))
    checked = 0
    for room in house.rooms:
        corners = np.asarray(room.polygon, np.float64)
        outer_x = outer_x_of_storey[room.level]
        for start, end in zip(corners, np.roll(corners, -1, axis=0), strict=True):
            if start[0] == end[0] == outer_x and abs(end[1] - start[1]) > 1.0:
                # 0.3 m beyond the middle of an outer wall at least 1 m long: that room's wall
                # is nearest, every other room's outline at least 0.5 m away.
                outside = (outer_x + 0.3, (start[1] + end[1]) / 2)
                assert index.rooms_at(np.array([outside]), room.floor_y)[0] == -1
                assert index.room_at(*outside, room.floor_y) == room
                checked += 1
    assert checked >= 3
