"""A two-storey house's flight of stairs and an episode that starts at its foot, shared by the
tests of features that must work on several storeys."""

from __future__ import annotations

import math
from dataclasses import dataclass

from vlln.sim.simulator import Simulator
from vlln.sim.storeys import Point3
from vlln.sim.viewpoints import storey_view_points
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.tasks.scenes import procedural_scene_id
from vlln.world.frame import yaw_of, yaw_to_quaternion

SCENE_ID = procedural_scene_id(1, 2)  # 24 rooms on two storeys, one flight along z


@dataclass(frozen=True)
class Flight:
    """A start on the ground floor in front of the flight, facing up it, and a point on the
    flight one metre past its foot (with the height of the tread there)."""

    start: Point3
    yaw: float
    on_flight: Point3


def flight_foot(sim: Simulator, before: float = 0.6, up: float = 1.0) -> Flight:
    storeys = sim.storeys
    assert storeys is not None
    flight = next(inst for inst in sim.house.instances if inst.category == "stairs")
    (x0, _, z0), (x1, _, z1) = flight.box.min, flight.box.max
    assert z1 - z0 > x1 - x0, "the flight of this house runs along z"
    x = (x0 + x1) / 2.0
    falls_toward_z1 = storeys.height_at(0, x, z1 - 0.1) < storeys.height_at(0, x, z0 + 0.1)
    foot, inward = (z1, -1.0) if falls_toward_z1 else (z0, 1.0)
    start = (x, storeys.floor_ys[0], foot - inward * before)
    gz = foot + inward * up
    on_flight = (x, storeys.height_at(0, x, gz), gz)
    return Flight(start, yaw_of(0.0, inward), on_flight)


def upstairs_episode(sim: Simulator, episode_id: str, near: float = 6.0) -> Episode:
    """An IIGN episode from the flight's foot to the first object upstairs whose view points
    are at least ``near`` metres away (first by instance id)."""
    storeys = sim.storeys
    assert storeys is not None
    flight = flight_foot(sim)
    x, y, z = flight.start
    for inst in sorted(sim.house.instances, key=lambda i: i.id):
        if inst.category == "stairs" or storeys.level_under(inst.box.min[1]) != 1:
            continue
        points = storey_view_points(storeys, inst.box)
        if not points or len(sim.house.instances_of(inst.category)) < 2:
            continue
        distance = sim.distance_field(points).distance(x, z, y)
        if near <= distance < math.inf:
            goal = Goal(
                inst.box.center,
                None,
                (*inst.box.min, *inst.box.max),
                tuple(ViewPoint(p) for p in points),
            )
            qx, qy, qz, qw = yaw_to_quaternion(flight.yaw)
            return Episode(
                episode_id,
                SCENE_ID,
                flight.start,
                (qx, qy, qz, qw),
                inst.category,
                (goal,),
                Instruction("iign", f"Search for the {inst.category}.", (str(inst.id),)),
                {"geodesic_distance": distance},
            )
    raise AssertionError("no object upstairs to search for")
