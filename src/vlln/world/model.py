"""The house model: rooms, doors, object instances and their relations.

These are plain records. A :class:`House` is the semantic side of a world (what the oracle and
the metrics read); its :class:`HouseGeometry` is what the simulator draws and walks on. Houses
imported from a scene summary have no geometry.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum

from vlln.world.catalogue.aliases import canonical_category
from vlln.world.mesh import Mesh

Point2 = tuple[float, float]  # floor-plan (x, z), see vlln.world.frame
Point3 = tuple[float, float, float]


def nearest_floor(floor_ys: Sequence[float], y: float) -> int:
    """Index of the floor height nearest ``y`` (the first on a tie): the storey of something
    at that height, so that halfway up a flight the agent passes to the storey above."""
    return min(range(len(floor_ys)), key=lambda k: (abs(floor_ys[k] - y), k))


MAX_RISE = 0.3  # m: a step taller than this is no step
FLOOR_MATCH = 0.05  # m: a scan's floor lies within this of its storey's floor height


def foot_on(floor_y: float, low: float) -> bool:
    """Whether a flight whose lowest point is at ``low`` starts from the floor at ``floor_y``:
    its foot is on that floor, or its first rise steps up from it (a scan's flight box often
    begins at the first tread)."""
    return floor_y - FLOOR_MATCH <= low <= floor_y + MAX_RISE


def top_at(floor_y: float, high: float) -> bool:
    """Whether a flight whose highest point is at ``high`` arrives on the floor at ``floor_y``:
    its top tread is level with that floor (a generated flight), or its last rise steps onto
    the floor, which is then the top landing (ordinary stairs, and how scans annotate them)."""
    return floor_y - MAX_RISE <= high <= floor_y + FLOOR_MATCH


class StructureId(IntEnum):
    """Instance ids of the house's structure in the instance-id image; objects are >= 1."""

    NOTHING = 0
    FLOOR = -1
    WALL = -2
    CEILING = -3
    DOOR_FRAME = -4


@dataclass(frozen=True)
class Box3:
    """Axis-aligned box, world frame, metres."""

    min: Point3
    max: Point3

    @property
    def center(self) -> Point3:
        return (
            (self.min[0] + self.max[0]) / 2.0,
            (self.min[1] + self.max[1]) / 2.0,
            (self.min[2] + self.max[2]) / 2.0,
        )

    @property
    def size(self) -> Point3:
        return (
            self.max[0] - self.min[0],
            self.max[1] - self.min[1],
            self.max[2] - self.min[2],
        )

    def expanded(self, margin: float) -> Box3:
        return Box3(
            (self.min[0] - margin, self.min[1] - margin, self.min[2] - margin),
            (self.max[0] + margin, self.max[1] + margin, self.max[2] + margin),
        )

    def plan_distance(self, x: float, z: float) -> float:
        """Floor-plan distance from a point to the box's footprint (0 inside it)."""
        dx = max(self.min[0] - x, 0.0, x - self.max[0])
        dz = max(self.min[2] - z, 0.0, z - self.max[2])
        return math.hypot(dx, dz)

    def distance_to(self, other: Box3) -> float:
        """Euclidean gap between the two boxes (0 when they touch or overlap)."""
        gap = [max(0.0, other.min[i] - self.max[i], self.min[i] - other.max[i]) for i in range(3)]
        return float(sum(g * g for g in gap) ** 0.5)


@dataclass(frozen=True)
class Attributes:
    """What a person can say about an instance; an empty string means unknown."""

    color: str = ""
    material: str = ""
    texture: str = ""
    shape: str = ""
    size: str = ""  # "small", "medium" or "large" relative to its category
    placement: str = ""  # e.g. "on the floor", "against the wall", "on the table"


@dataclass(frozen=True)
class Room:
    """A room: its type (``"bedroom"``, ...), floor-plan polygon and floor height."""

    id: int
    type: str
    polygon: tuple[Point2, ...]
    floor_y: float = 0.0
    ceiling_height: float = 2.7
    level: int = 0  # storey index; 0 is the ground floor

    @property
    def name(self) -> str:
        return self.type


@dataclass(frozen=True)
class Door:
    """An opening in the wall between two rooms (``room_b`` is -1 for an outside door)."""

    id: int
    room_a: int
    room_b: int
    center: Point2
    width: float
    axis: str  # the wall the door is in runs along "x" or "z"


@dataclass(frozen=True)
class ObjectInstance:
    """One object in the house with everything needed to talk about it."""

    id: int  # >= 1, also its value in the instance-id image
    category: str
    fine_category: str
    attributes: Attributes
    caption: str
    box: Box3
    room_id: int
    yaw: float = 0.0
    support_id: int | None = None  # the instance it stands on, if any

    @property
    def position(self) -> Point3:
        return self.box.center


@dataclass(frozen=True)
class Relation:
    """``subject <word> object``, e.g. ``cup on table``; instances within 1 m of each other."""

    subject: int
    word: str  # "on", "under", "next to", "near", "above"
    object: int
    distance: float


@dataclass
class HouseGeometry:
    """What the simulator needs: one static mesh for the whole house."""

    mesh: Mesh


@dataclass
class House:
    """A world: rooms, doors, instances and relations, plus geometry when it was generated."""

    name: str
    rooms: list[Room]
    doors: list[Door]
    instances: list[ObjectInstance]
    relations: list[Relation] = field(default_factory=list)
    geometry: HouseGeometry | None = None
    seed: int | None = None
    # Instance ids as a file spells them ("3/chair_12") -> our integer ids.
    instance_keys: dict[str, int] = field(default_factory=dict)

    def instance(self, instance_id: int) -> ObjectInstance:
        for inst in self.instances:
            if inst.id == instance_id:
                return inst
        raise KeyError(f"house {self.name!r} has no instance {instance_id}")

    def instance_for_key(self, key: str) -> ObjectInstance:
        """The instance an episode file names: by a key of :attr:`instance_keys`, a decimal
        id, or the trailing number of a key like ``"3/chair_12"`` (the scan's object index)."""
        if key in self.instance_keys:
            return self.instance(self.instance_keys[key])
        tail = key.rsplit("_", 1)[-1].rsplit("/", 1)[-1].strip()
        if tail.isdecimal():
            return self.instance(int(tail))
        raise KeyError(f"house {self.name!r} has no instance {key!r}")

    def room(self, room_id: int) -> Room:
        for room in self.rooms:
            if room.id == room_id:
                return room
        raise KeyError(f"house {self.name!r} has no room {room_id}")

    def instances_of(self, category: str) -> list[ObjectInstance]:
        """The instances of a category, also when it is named by an alias ("sofa")."""
        name = canonical_category(category)
        return [inst for inst in self.instances if canonical_category(inst.category) == name]
