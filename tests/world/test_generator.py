"""Tests of whole generated houses: determinism, doors, walls, objects and walkability."""

from __future__ import annotations

from collections import Counter, deque
from collections.abc import Iterator

import numpy as np
import pytest
from numpy.typing import NDArray

from vlln.sim.navgrid import NavGrid
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.generator.rect import Rect
from vlln.world.generator.structure import DOOR_HEIGHT
from vlln.world.model import House, ObjectInstance, StructureId

SMALL = HouseParameters(min_rooms=3, max_rooms=5, min_area=40.0, max_area=70.0)
TALL = HouseParameters(min_rooms=4, max_rooms=6, ceiling_height=3.0, wall_thickness=0.15)
FLAT = 0.05  # m; rugs and mats lower than this are walked over, also in doorways
FLOOR_WORDS = ("against the wall", "on the floor", "at the table", "in the corner")


@pytest.fixture(scope="module")
def houses() -> list[House]:
    return [generate_house(0), generate_house(2, SMALL), generate_house(3, TALL)]


def each_house(
    houses: list[House],
) -> Iterator[tuple[House, NDArray[np.float64], NDArray[np.int32]]]:
    for house in houses:
        assert house.geometry is not None
        mesh = house.geometry.mesh
        yield house, mesh.positions.reshape(-1, 3, 3).astype(np.float64), mesh.instance_ids[::3]


def triangles_crossing_box(
    triangles: NDArray[np.float64], lo: NDArray[np.float64], hi: NDArray[np.float64]
) -> NDArray[np.bool_]:
    """Separating-axis test: which triangles pass through the open box ``(lo, hi)``."""
    centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
    near = (triangles.min(1) < hi).all(1) & (triangles.max(1) > lo).all(1)
    crossing = np.zeros(len(triangles), bool)
    v = triangles[near] - centre
    separated = np.zeros(len(v), bool)  # the box's own axes are the prefilter above
    edges = [v[:, 1] - v[:, 0], v[:, 2] - v[:, 1], v[:, 0] - v[:, 2]]
    axes = [np.cross(edges[0], edges[1])]
    axes += [np.cross(e, np.eye(3)[a]) for e in edges for a in range(3)]
    for axis in axes:
        radius = (np.abs(axis) * half).sum(1)
        projected = np.einsum("nij,nj->ni", v, axis)
        real = radius > 1e-12
        separated |= real & ((projected.min(1) >= radius) | (projected.max(1) <= -radius))
    crossing[near] = ~separated
    return crossing


def test_the_box_test_sees_a_wall_through_an_opening() -> None:
    wall = np.array([[[-5.0, 0.0, 0.0], [5.0, 0.0, 0.0], [5.0, 3.0, 0.0]]])
    box_lo, box_hi = np.array([-0.4, 0.1, -0.1]), np.array([0.4, 2.0, 0.1])
    assert triangles_crossing_box(wall, box_lo, box_hi).all()
    assert not triangles_crossing_box(wall + np.array([0.0, 0.0, 0.5]), box_lo, box_hi).any()


def test_same_seed_gives_identical_records_and_mesh() -> None:
    a, b = generate_house(11, SMALL), generate_house(11, SMALL)
    assert a.name == b.name == "house_00011"
    assert (a.rooms, a.doors, a.instances, a.relations) == (
        b.rooms,
        b.doors,
        b.instances,
        b.relations,
    )
    assert a.geometry is not None and b.geometry is not None
    for field in ("positions", "normals", "uvs", "colors", "materials", "instance_ids"):
        assert (
            getattr(a.geometry.mesh, field).tobytes() == getattr(b.geometry.mesh, field).tobytes()
        )


@pytest.mark.slow
def test_different_seeds_give_different_houses(houses: list[House]) -> None:
    other = generate_house(12, SMALL)
    small = houses[1]
    assert other.rooms != small.rooms
    assert [i.caption for i in other.instances] != [i.caption for i in small.instances]


def test_parameters_shape_the_house(houses: list[House]) -> None:
    for house, params in zip(houses, (HouseParameters(), SMALL, TALL), strict=True):
        area = sum(Rect.of_room(room).area for room in house.rooms)
        assert params.min_rooms <= len(house.rooms) <= params.max_rooms
        assert params.min_area - 1e-6 <= area <= params.max_area + 1e-6
        assert house.geometry is not None
        ceiling = house.geometry.mesh.positions[
            house.geometry.mesh.instance_ids == StructureId.CEILING
        ]
        assert np.allclose(ceiling[:, 1], params.ceiling_height)
        assert {d.width for d in house.doors} == {params.door_width}


def test_every_room_is_reachable_through_doors(houses: list[House]) -> None:
    for house in houses:
        neighbours: dict[int, set[int]] = {room.id: set() for room in house.rooms}
        for door in house.doors:
            neighbours[door.room_a].add(door.room_b)
            neighbours[door.room_b].add(door.room_a)
        seen, queue = {0}, deque([0])
        while queue:
            for nxt in neighbours[queue.popleft()] - seen:
                seen.add(nxt)
                queue.append(nxt)
        assert seen == set(neighbours)


def test_door_openings_are_open_up_to_the_lintel(houses: list[House]) -> None:
    for house, triangles, _ in each_house(houses):
        for door in house.doors:
            half = door.width / 2.0 - 0.005  # the clear width, a hair inside the jambs
            x, z = door.center
            if door.axis == "x":
                lo, hi = (
                    np.array([x - half, FLAT, z - 0.4]),
                    np.array([x + half, DOOR_HEIGHT - 0.01, z + 0.4]),
                )
            else:
                lo, hi = (
                    np.array([x - 0.4, FLAT, z - half]),
                    np.array([x + 0.4, DOOR_HEIGHT - 0.01, z + half]),
                )
            crossing = triangles_crossing_box(triangles, lo, hi)
            assert not crossing.any(), (house.name, door)


def test_walls_are_closed_apart_from_the_doors(houses: list[House]) -> None:
    """Horizontal rays through every room side at 1 m height hit a wall, except at doors."""
    for house, triangles, ids in each_house(houses):
        walls = triangles[ids == StructureId.WALL]
        for room in house.rooms:
            r = Rect.of_room(room)
            for axis, coord, lo, hi, inward in (
                ("x", r.z0, r.x0, r.x1, 1.0),
                ("x", r.z1, r.x0, r.x1, -1.0),
                ("z", r.x0, r.z0, r.z1, 1.0),
                ("z", r.x1, r.z0, r.z1, -1.0),
            ):
                along = np.linspace(lo, hi, max(2, round((hi - lo) / 0.1)))
                for door in house.doors:
                    d_along, d_coord = door.center if door.axis == "x" else door.center[::-1]
                    if door.axis == axis and abs(d_coord - coord) < 1e-9:
                        along = along[np.abs(along - d_along) > door.width / 2.0 + 0.06]
                starts = np.zeros((len(along), 3))
                starts[:, 1] = 1.0
                a, c = (0, 2) if axis == "x" else (2, 0)
                starts[:, a] = along
                starts[:, c] = coord + 0.3 * inward
                direction = np.zeros(3)
                direction[c] = -inward
                hit = rays_hit(starts, direction, 0.6, walls)
                assert hit.all(), (house.name, room.type, axis, coord, along[~hit])


def rays_hit(
    starts: NDArray[np.float64],
    direction: NDArray[np.float64],
    length: float,
    triangles: NDArray[np.float64],
) -> NDArray[np.bool_]:
    """Möller-Trumbore: whether each ray ``start + t * direction, 0 <= t <= length`` hits."""
    v0, e1, e2 = (
        triangles[:, 0],
        triangles[:, 1] - triangles[:, 0],
        triangles[:, 2] - triangles[:, 0],
    )
    p = np.cross(direction, e2)
    det = (e1 * p).sum(1)
    ok = np.abs(det) > 1e-12
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = starts[:, None, :] - v0[None]
    u = (s * p[None]).sum(2) * inv
    q = np.cross(s, e1[None])
    v = (q * direction).sum(2) * inv
    t = (q * e2[None]).sum(2) * inv
    inside = ok & (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9) & (t >= 0) & (t <= length)
    return inside.any(1)


def floor_objects(house: House) -> list[ObjectInstance]:
    return [
        inst
        for inst in house.instances
        if inst.attributes.placement in FLOOR_WORDS and inst.box.size[1] >= FLAT
    ]


def test_no_two_floor_objects_overlap(houses: list[House]) -> None:
    for house in houses:
        objects = floor_objects(house)
        assert len(objects) >= len(house.rooms)
        lo = np.array([[o.box.min[0], o.box.min[2]] for o in objects])
        hi = np.array([[o.box.max[0], o.box.max[2]] for o in objects])
        overlap = np.clip(
            np.minimum(hi[:, None], hi[None]) - np.maximum(lo[:, None], lo[None]), 0, None
        )
        area = overlap.prod(axis=2)
        np.fill_diagonal(area, 0.0)
        assert area.max() < 1e-6, [
            (objects[i].category, objects[j].category) for i, j in np.argwhere(area >= 1e-6)
        ]


def test_objects_lie_inside_their_room_and_below_the_ceiling(houses: list[House]) -> None:
    for house in houses:
        for inst in house.instances:
            room = house.room(inst.room_id)
            r = Rect.of_room(room)
            b = inst.box
            assert r.x0 - 1e-4 <= b.min[0] and b.max[0] <= r.x1 + 1e-4, inst
            assert r.z0 - 1e-4 <= b.min[2] and b.max[2] <= r.z1 + 1e-4, inst
            assert b.min[1] >= -1e-4 and b.max[1] <= room.ceiling_height + 1e-4, inst


def test_objects_on_surfaces_rest_on_their_support(houses: list[House]) -> None:
    checked = 0
    for house, triangles, ids in each_house(houses):
        normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        upward = normals[:, 1] > 0.9 * np.linalg.norm(normals, axis=1)
        for inst in house.instances:
            if inst.support_id is None:
                continue
            support = house.instance(inst.support_id)
            assert inst.attributes.placement == f"on the {support.category}"
            assert support.room_id == inst.room_id
            b, s = inst.box, support.box
            assert s.min[0] - 0.01 <= b.min[0] and b.max[0] <= s.max[0] + 0.01
            assert s.min[2] - 0.01 <= b.min[2] and b.max[2] <= s.max[2] + 0.01
            tops = triangles[(ids == support.id) & upward]
            level = np.abs(tops[:, :, 1].mean(1) - b.min[1]) <= 0.01
            under = (
                (tops[:, :, 0].min(1) < b.max[0])
                & (tops[:, :, 0].max(1) > b.min[0])
                & (tops[:, :, 2].min(1) < b.max[2])
                & (tops[:, :, 2].max(1) > b.min[2])
            )
            assert (level & under).any(), (house.name, inst.category, support.category)
            checked += 1
    assert checked > 20


def test_instances_match_the_mesh(houses: list[House]) -> None:
    for house, triangles, ids in each_house(houses):
        assert [inst.id for inst in house.instances] == list(range(1, len(house.instances) + 1))
        assert set(np.unique(ids[ids > 0])) == {inst.id for inst in house.instances}
        for inst in house.instances:
            points = triangles[ids == inst.id].reshape(-1, 3)
            assert np.allclose(points.min(0), inst.box.min, atol=1e-6)
            assert np.allclose(points.max(0), inst.box.max, atol=1e-6)
            assert inst.caption.endswith(f" in the {house.room(inst.room_id).type}.") or (
                inst.caption.endswith(f" of the {house.room(inst.room_id).type}.")
            )


def test_many_categories_have_several_instances(houses: list[House]) -> None:
    for house in (houses[0], houses[2]):
        counts = Counter(inst.category for inst in house.instances)
        assert len(house.instances) >= 60
        assert sum(1 for n in counts.values() if n >= 2) >= 10
        assert max(counts.values()) >= 4


def test_relations_join_supported_objects(houses: list[House]) -> None:
    for house in houses:
        on = {(r.subject, r.object) for r in house.relations if r.word == "on"}
        for inst in house.instances:
            if inst.support_id is not None:
                assert (inst.id, inst.support_id) in on


def test_navigable_area_is_one_component_reaching_every_room(houses: list[House]) -> None:
    for house in houses:
        assert house.geometry is not None
        grid = NavGrid.from_mesh(house.geometry.mesh)
        labels, _ = grid.components()
        main = grid.largest_component()
        navigable = np.count_nonzero(labels)
        assert np.count_nonzero(labels == main) >= 0.95 * navigable, house.name
        for room in house.rooms:
            r = Rect.of_room(room)
            row0, col0 = grid.world_to_cell(r.x0, r.z0)
            row1, col1 = grid.world_to_cell(r.x1, r.z1)
            cells = np.count_nonzero(labels[row0:row1, col0:col1] == main)
            assert cells * grid.cell_size**2 >= 0.5, (house.name, room.type)
