"""Axis-aligned floor-plan rectangles: rooms, footprints, clear zones."""

from __future__ import annotations

from dataclasses import dataclass

from vlln.world.model import Room


@dataclass(frozen=True)
class Rect:
    """An axis-aligned floor-plan rectangle ``[x0, x1] x [z0, z1]``, metres."""

    x0: float
    z0: float
    x1: float
    z1: float

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    @property
    def depth(self) -> float:
        return self.z1 - self.z0

    @property
    def area(self) -> float:
        return self.width * self.depth

    @property
    def polygon(self) -> tuple[tuple[float, float], ...]:
        return ((self.x0, self.z0), (self.x1, self.z0), (self.x1, self.z1), (self.x0, self.z1))

    def shrunk(self, margin: float) -> Rect:
        return Rect(self.x0 + margin, self.z0 + margin, self.x1 - margin, self.z1 - margin)

    @staticmethod
    def of_room(room: Room) -> Rect:
        xs = [p[0] for p in room.polygon]
        zs = [p[1] for p in room.polygon]
        return Rect(min(xs), min(zs), max(xs), max(zs))
