"""The flights of stairs the collector can take, each with a place to stand at either end.

A flight's instance box spans its treads, from the lower storey's floor to the upper one's;
it climbs along the box's longer side. Its foot is the end whose first tread is lower. The
collector walks from the landing in front of one end to the landing beyond the other, so a
flight is one more place to go to, beside the frontiers of the storey it starts on, and
:class:`FlightChoices` says when it may be chosen.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from vlln.datagen.collector.storey_maps import StoreyMaps
from vlln.sim.storeys import Point3, Storeys
from vlln.world.model import House, ObjectInstance

STAIRS_CATEGORY = "stairs"
_LANDING_DEPTH = 0.5  # m in front of the first (beyond the last) tread where one stands
_END_INSET = 0.1  # m inside the box where the end treads' heights are read


@dataclass(frozen=True)
class Flight:
    """A flight joining storey ``lower`` to ``upper``, and where to stand at each end."""

    instance_id: int
    lower: int
    upper: int
    foot: Point3  # on the lower storey's floor, in front of the first tread
    head: Point3  # on the upper storey's floor, beyond the last tread

    def joins(self, level: int) -> bool:
        return level in (self.lower, self.upper)

    def end_on(self, level: int) -> Point3:
        """Where to stand to take the flight from storey ``level``."""
        return self.foot if level == self.lower else self.head

    def leads_to(self, level: int) -> int:
        """The storey the flight leads to from storey ``level``."""
        return self.upper if level == self.lower else self.lower

    def arrival(self, level: int) -> Point3:
        """Where taking the flight from storey ``level`` ends."""
        return self.end_on(self.leads_to(level))


def house_flights(house: House, storeys: Storeys) -> list[Flight]:
    """Every flight of the house, in instance id order."""
    return [
        _flight(instance, storeys)
        for instance in sorted(house.instances, key=lambda i: i.id)
        if instance.category == STAIRS_CATEGORY
    ]


def _flight(instance: ObjectInstance, storeys: Storeys) -> Flight:
    box = instance.box
    lower, upper = storeys.level_of(box.min[1]), storeys.level_of(box.max[1])
    centre = ((box.min[0] + box.max[0]) / 2.0, (box.min[2] + box.max[2]) / 2.0)
    along_x = box.max[0] - box.min[0] >= box.max[2] - box.min[2]
    half = (box.max[0] - box.min[0] if along_x else box.max[2] - box.min[2]) / 2.0
    axis = (1.0, 0.0) if along_x else (0.0, 1.0)

    def end(sign: float, beyond: float) -> tuple[float, float]:
        reach = sign * (half + beyond)
        return centre[0] + axis[0] * reach, centre[1] + axis[1] * reach

    inside = -_END_INSET
    rises = storeys.height_at(lower, *end(1.0, inside)) > storeys.height_at(
        lower, *end(-1.0, inside)
    )
    up = 1.0 if rises else -1.0
    fx, fz = end(-up, _LANDING_DEPTH)
    hx, hz = end(up, _LANDING_DEPTH)
    foot = storeys.snap_point(fx, storeys.floor_ys[lower], fz)
    head = storeys.snap_point(hx, storeys.floor_ys[upper], hz)
    return Flight(instance.id, lower, upper, foot, head)


class FlightChoices:
    """Which flights the collector may take from a storey: those whose landing its map of
    that storey shows (a level camera does not see treads that go down from its feet), each
    at most ``max_climbs`` times from one storey. ``to_target`` is the walk from a place to
    the target (privileged, like the chooser's ground-truth branch)."""

    def __init__(
        self,
        flights: list[Flight],
        start_level: int,
        to_target: Callable[[Point3], float],
        max_climbs: int = 2,
    ) -> None:
        self.flights = flights
        self.to_target = to_target
        self.max_climbs = max_climbs
        self._levels_seen = {start_level}
        self._seen: set[tuple[int, int]] = set()  # (storey, flight) whose landing is mapped
        self._climbs: dict[tuple[int, int], int] = {}  # (storey, flight): times taken

    def note(self, level: int, maps: StoreyMaps) -> None:
        """Mark the flights whose landing on storey ``level`` its map now shows."""
        for flight in self.flights:
            x, _, z = flight.end_on(level)
            if flight.joins(level) and maps.explored_at(level, x, z):
                self._seen.add((level, flight.instance_id))

    def first_visit(self, level: int) -> bool:
        """True the first time a storey is reached (the start's storey counts as reached)."""
        first = level not in self._levels_seen
        self._levels_seen.add(level)
        return first

    def toward_target(self, level: int) -> Flight | None:
        """A flight seen from storey ``level`` whose far end is nearer the target."""
        for flight in self.flights:
            if (level, flight.instance_id) in self._seen and self._may_take(flight, level):
                far = self.to_target(flight.arrival(level))
                if far < self.to_target(flight.end_on(level)):
                    return flight
        return None

    def options(self, level: int, exhausted: bool) -> list[Flight]:
        """Flights offered to the chooser from storey ``level``: all of them, once the
        storey has no frontier left (so a storey explored in vain is left)."""
        if not exhausted:
            return []
        return [flight for flight in self.flights if self._may_take(flight, level)]

    def nearer_end(self, level: int) -> tuple[Flight, Point3] | None:
        """For an agent on the stairs: the end of a flight of its storey nearer the target."""
        ends = [(f, end) for f in self.flights if f.joins(level) for end in (f.foot, f.head)]
        if not ends:
            return None
        return min(ends, key=lambda pair: (self.to_target(pair[1]), pair[1]))

    def took(self, flight: Flight, level: int) -> None:
        key = (level, flight.instance_id)
        self._climbs[key] = self._climbs.get(key, 0) + 1

    def _may_take(self, flight: Flight, level: int) -> bool:
        taken = self._climbs.get((level, flight.instance_id), 0)
        return flight.joins(level) and taken < self.max_climbs
