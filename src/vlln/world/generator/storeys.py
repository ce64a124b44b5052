"""Houses of two or three storeys joined by straight flights of stairs.

Every storey has the ground floor's room rectangles and inner doors (so the walls stand on
each other); the upper storeys give the rooms other uses (the kitchen becomes a study, ...)
and are furnished on their own. A flight joins storey ``k`` to ``k + 1`` inside a room large
enough for it and its two landings; on three storeys the two flights stand apart. Objects
that would stand on a flight or its landings are left out, and instance ids are numbered
1..N over the whole house, the staircases last (category ``stairs``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from vlln.errors import HouseParametersError
from vlln.world.catalogue.registry import Catalogue
from vlln.world.generator.furnishing import FurnishedObject, furnish
from vlln.world.generator.layout import FloorPlan, plan_floor
from vlln.world.generator.params import HouseParameters
from vlln.world.generator.rect import Rect
from vlln.world.generator.stairs import (
    StairSite,
    flight_mesh,
    overlaps,
    shaft_mesh,
    stair_sites,
    storey_height,
    without_area,
)
from vlln.world.generator.structure import build_structure
from vlln.world.mesh import Mesh
from vlln.world.model import Attributes, Box3, Door, ObjectInstance, Room, StructureId

# What a room of the storey below becomes on the storey above.
UPPER_ROOM_TYPE: dict[str, str] = {
    "living room": "living room",
    "kitchen": "study",
    "dining room": "bedroom",
    "bedroom": "bedroom",
    "bathroom": "bathroom",
    "toilet": "toilet",
    "study": "bedroom",
    "storage room": "storage room",
    "gym": "gym",
    "corridor": "corridor",
}
STAIR_COLORS = ("brown", "dark brown", "beige")
_PLAN_ATTEMPTS = 40


def storey_plans(
    params: HouseParameters, rng: np.random.Generator
) -> tuple[list[FloorPlan], list[StairSite]]:
    """One plan per storey (ids numbered across storeys) and the flights between them."""
    for _ in range(_PLAN_ATTEMPTS):
        ground = plan_floor(params, rng)
        sites = _choose_sites(ground, params, rng)
        if sites is not None:
            return _stack(ground, params), sites
    raise HouseParametersError(
        f"no floor plan with room for {params.floors - 1} flight(s) of stairs was found; "
        "raise min_area (a flight needs a room of about 6 x 2.4 m) or lower floors"
    )


def _choose_sites(
    plan: FloorPlan, params: HouseParameters, rng: np.random.Generator
) -> list[StairSite] | None:
    candidates = stair_sites(plan, params.wall_thickness)
    chosen: list[StairSite] = []
    for _ in range(params.floors - 1):
        free = [s for s in candidates if not any(overlaps(s.keep_out, c.keep_out) for c in chosen)]
        if not free:
            return None
        chosen.append(free[int(rng.integers(len(free)))])
    return chosen


def _stack(ground: FloorPlan, params: HouseParameters) -> list[FloorPlan]:
    n = len(ground.rooms)
    height = storey_height(params.ceiling_height)
    plans = [ground]
    for level in range(1, params.floors):
        below = plans[-1]
        rooms = [
            Room(
                room.id + n,
                UPPER_ROOM_TYPE.get(room.type, room.type),
                room.polygon,
                level * height,
                room.ceiling_height,
                level,
            )
            for room in below.rooms
        ]
        doors = [
            Door(
                door.id + len(ground.doors),
                door.room_a + n,
                door.room_b + n,
                door.center,
                door.width,
                door.axis,
            )
            for door in below.doors
            if door.room_b >= 0 and door.room_a >= 0
        ]
        plans.append(FloorPlan(rooms, doors))
    return plans


def build_storeys(
    params: HouseParameters,
    catalogue: Catalogue,
    plan_rng: np.random.Generator,
    shell_rng: np.random.Generator,
    furniture_rng: np.random.Generator,
) -> tuple[list[Room], list[Door], list[ObjectInstance], Mesh]:
    """Rooms, doors, instances and mesh of a house with ``params.floors`` storeys."""
    plans, sites = storey_plans(params, plan_rng)
    height = storey_height(params.ceiling_height)
    shells: list[Mesh] = []
    objects: list[FurnishedObject] = []
    for level, plan in enumerate(plans):
        shell = build_structure(_at_ground(plan), params, shell_rng)
        for k, site in enumerate(sites):
            room = plan.rects[site.room]
            if k == level:  # the flight starts here: open the ceiling above it
                shell = without_area(shell, StructureId.CEILING, room, site.rect)
            if k == level - 1:  # the flight arrives here: open the floor
                shell = without_area(shell, StructureId.FLOOR, room, site.rect)
        shells.append(shell.transformed(0.0, (0.0, level * height, 0.0)))
        keep_out = [s.keep_out for k, s in enumerate(sites) if k in (level, level - 1)]
        placed = furnish(_at_ground(plan), params, catalogue, furniture_rng)
        objects += _renumbered(_clear_of(placed, keep_out), len(objects) + 1, level * height)
    instances = [obj.instance for obj in objects]
    meshes = [obj.mesh for obj in objects]
    for k, site in enumerate(sites):
        bottom, top = k * height, (k + 1) * height
        color = STAIR_COLORS[int(shell_rng.integers(len(STAIR_COLORS)))]
        stair_id = len(instances) + 1
        meshes.append(flight_mesh(site, bottom, top, color).with_instance_id(stair_id))
        shells.append(shaft_mesh(site, bottom, top, params.ceiling_height, params.wall_thickness))
        instances.append(_staircase(stair_id, site, bottom, top, color, plans[k].rooms[site.room]))
    rooms = [room for plan in plans for room in plan.rooms]
    doors = [door for plan in plans for door in plan.doors]
    return rooms, doors, instances, Mesh.concatenate([*shells, *meshes])


def _at_ground(plan: FloorPlan) -> FloorPlan:
    """The plan with its rooms at height 0, as the shell builder and furnisher expect."""
    return FloorPlan([replace(room, floor_y=0.0) for room in plan.rooms], plan.doors)


def _clear_of(placed: list[FurnishedObject], zones: list[Rect]) -> list[FurnishedObject]:
    """Objects whose footprint misses every zone, and whose support (if any) is kept."""
    kept: list[FurnishedObject] = []
    kept_ids: set[int] = set()
    for obj in placed:  # supports are placed before what stands on them
        box = obj.instance.box
        foot = Rect(box.min[0], box.min[2], box.max[0], box.max[2])
        support = obj.instance.support_id
        if any(overlaps(foot, zone) for zone in zones):
            continue
        if support is not None and support not in kept_ids:
            continue
        kept.append(obj)
        kept_ids.add(obj.instance.id)
    return kept


def _renumbered(placed: list[FurnishedObject], first_id: int, dy: float) -> list[FurnishedObject]:
    """A storey's objects raised by ``dy`` with ids from ``first_id`` on, supports included."""
    new_id = {obj.instance.id: first_id + k for k, obj in enumerate(placed)}
    moved: list[FurnishedObject] = []
    for obj in placed:
        old = obj.instance
        lo, hi = old.box.min, old.box.max
        instance = replace(
            old,
            id=new_id[old.id],
            support_id=None if old.support_id is None else new_id[old.support_id],
            box=Box3((lo[0], lo[1] + dy, lo[2]), (hi[0], hi[1] + dy, hi[2])),
        )
        mesh = obj.mesh.transformed(0.0, (0.0, dy, 0.0)).with_instance_id(instance.id)
        moved.append(FurnishedObject(instance, mesh))
    return moved


def _staircase(
    instance_id: int, site: StairSite, bottom: float, top: float, color: str, room: Room
) -> ObjectInstance:
    r = site.rect
    return ObjectInstance(
        id=instance_id,
        category="stairs",
        fine_category="staircase",
        attributes=Attributes(
            color=color,
            material="wood",
            shape="straight",
            size="large",
            placement="against the wall",
        ),
        caption=f"a straight {color} wooden staircase going up to the next floor",
        box=Box3((r.x0, bottom, r.z0), (r.x1, top, r.z1)),
        room_id=room.id,
    )
