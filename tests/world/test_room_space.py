"""Tests of the per-room placement rules: walls, door zones and walkable floor."""

from __future__ import annotations

from vlln.world.generator.rect import Rect
from vlln.world.generator.room_space import RoomSpace
from vlln.world.model import Box3, Door

ROOM = Rect(0.0, 0.0, 5.0, 4.0)
# One door in the wall z = 0 near x = 1, one in the wall z = 4 near x = 4.
DOORS = [
    Door(0, 0, 1, (1.0, 0.0), 0.9, "x"),
    Door(1, 0, 2, (4.0, 4.0), 0.9, "x"),
]


def space() -> RoomSpace:
    return RoomSpace.of_room(ROOM, 2.7, 0.1, DOORS, room_id=0)


def box(x0: float, z0: float, x1: float, z1: float, y0: float = 0.0, y1: float = 0.8) -> Box3:
    return Box3((x0, y0, z0), (x1, y1, z1))


def test_a_small_object_in_a_free_corner_fits() -> None:
    s = space()
    b = box(4.2, 0.06, 4.94, 0.6)
    assert s.fits_floor(b)
    assert s.keeps_floor_walkable(Rect(4.2, 0.06, 4.94, 0.6))


def test_objects_must_stay_inside_the_walls() -> None:
    assert not space().fits_floor(box(4.5, 1.0, 5.2, 1.5))  # through the wall x = 5
    assert not space().fits_floor(box(1.0, 1.0, 2.0, 2.0, y1=2.8))  # through the ceiling


def test_door_zones_stay_clear() -> None:
    s = space()
    assert not s.fits_floor(box(0.8, 0.3, 1.3, 0.8))  # right in front of door 0
    assert not s.fits_floor(box(3.8, 3.2, 4.3, 3.7))  # right in front of door 1
    assert s.fits_floor(box(2.0, 1.5, 2.5, 2.0))


def test_a_barrier_between_the_doors_is_rejected() -> None:
    s = space()
    wall_to_wall = Rect(0.05, 1.8, 4.95, 2.3)
    assert not s.keeps_floor_walkable(wall_to_wall)
    half_way = Rect(0.05, 1.8, 2.5, 2.3)
    assert s.keeps_floor_walkable(half_way)


def test_cutting_off_a_large_pocket_is_rejected() -> None:
    s = space()
    # A U of furniture around the corner x > 3, z < 2 leaves a walled-in pocket of floor.
    s.add_floor_object(1, box(2.6, 0.05, 3.0, 2.4))
    s.add_floor_object(2, box(3.0, 2.0, 4.6, 2.4))
    closing = Rect(4.6, 2.0, 4.95, 2.4)
    assert not s.keeps_floor_walkable(closing)


def test_placed_objects_block_later_ones() -> None:
    s = space()
    s.add_floor_object(1, box(2.0, 1.5, 3.0, 2.5))
    assert not s.fits_floor(box(2.5, 2.0, 3.5, 3.0))
    assert s.fits_floor(box(3.2, 1.5, 3.8, 2.5))
    picture = box(2.2, 1.9, 2.8, 2.1, y0=1.6, y1=2.0)
    assert s.fits_above_floor(picture, hangs=True)
    assert not s.fits_above_floor(box(2.2, 1.9, 2.8, 2.1, y0=0.5, y1=1.0))


def test_low_hanging_objects_count_as_obstacles() -> None:
    s = space()
    low_shelf_at_door = box(0.6, 0.05, 1.4, 0.3, y0=1.2, y1=1.4)
    assert not s.fits_above_floor(low_shelf_at_door, hangs=True)
    high_shelf_at_door = box(0.6, 0.05, 1.4, 0.3, y0=2.2, y1=2.4)
    assert s.fits_above_floor(high_shelf_at_door, hangs=True)
