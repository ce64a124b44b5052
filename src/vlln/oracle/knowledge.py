"""What the rule oracle knows during an episode, arranged so that every answer is a look-up.

A :class:`HouseIndex` is built once per house (rooms as polygons, instances by id, the
relation graph by instance, landmark objects per room); an :class:`EpisodeKnowledge` adds the
target, the geodesic field to its view points and the shortest-path follower. Both are built
when an episode starts, so answering a question does no search beyond one path query.
"""

from __future__ import annotations

import re
import zlib
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vlln.sim.follower import GreedyFollower
from vlln.sim.geodesic import GeodesicField
from vlln.sim.storey_field import StoreyField
from vlln.tasks.oracle_protocol import EpisodeContext
from vlln.world.catalogue.aliases import aliases_of
from vlln.world.model import House, ObjectInstance, Relation, Room

# Landmarks for route descriptions: big enough to notice from across a room, not so high up
# that a walker would not look at them (reference: at most 2 m above the floor), and not
# lights, which hang everywhere and name no place.
LANDMARK_MIN_SIZE = 0.5  # m, largest side of the box
LANDMARK_MAX_HEIGHT = 2.0  # m, bottom of the box above the room's floor
_NOT_LANDMARK_WORDS = ("light", "ceiling", "wall", "floor", "column")
# Category names that are also auxiliary verbs: followed by a subject or "be"/"not" ("can it
# be ...?", "can you see it?") the word is the verb, not the object.
_AUXILIARY_NAMES = frozenset({"can"})
_AUXILIARY_USE = r"(?!\s+(?:i|you|we|they|it|he|she|one|be|not)\b)"

# How rooms are spoken; a type without an entry is spoken as it is written.
_SPOKEN_ROOM = {"other": "open area", "stairs": "staircase"}


def room_name(room: Room) -> str:
    """How a person names the room's type: "kitchen", "living room"."""
    return _SPOKEN_ROOM.get(room.type, room.type)


def object_phrase(instance: ObjectInstance) -> str:
    """The category with one attribute, the colour when known: "the white sofa"."""
    attributes = instance.attributes
    adjective = attributes.color or material_adjective(attributes.material)
    return f"the {adjective} {instance.category}" if adjective else f"the {instance.category}"


def material_adjective(material: str) -> str:
    """The adjective for a material ("wooden"); empty for paint and leaves."""
    return _MATERIAL_ADJECTIVE.get(material, material)


_MATERIAL_ADJECTIVE = {
    "plain": "",
    "foliage": "",
    "wood": "wooden",
    "tile": "tiled",
    "carpet": "carpeted",
}


def choose(rng: np.random.Generator, variants: tuple[str, ...]) -> str:
    """One of several wordings; the episode's generator keeps the choice reproducible."""
    return variants[int(rng.integers(len(variants)))]


@dataclass(frozen=True)
class _RoomEdges:
    """The outline edges of several rooms, one array, each room's edges together, so that one
    array expression tests a point against every room."""

    start: NDArray[np.float64]  # (edges, 2)
    end: NDArray[np.float64]  # (edges, 2)
    first_edge: NDArray[np.int64]  # (rooms,) where each room's edges begin
    room_ids: NDArray[np.int64]  # (rooms,) in the house's order

    @staticmethod
    def of(rooms: list[Room]) -> _RoomEdges:
        starts = [np.asarray(room.polygon, np.float64) for room in rooms]
        counts = [len(start) for start in starts]
        return _RoomEdges(
            np.concatenate([np.zeros((0, 2)), *starts]),
            np.concatenate([np.zeros((0, 2)), *(np.roll(start, -1, axis=0) for start in starts)]),
            np.cumsum([0, *counts[:-1]], dtype=np.int64),
            np.array([room.id for room in rooms], np.int64),
        )

    def first_room_containing(self, points: NDArray[np.float64]) -> NDArray[np.int64]:
        """For each point ``(n, 2)``, the first room (in the house's order) whose outline
        contains it by the even-odd rule; -1 where none does."""
        if not len(self.room_ids):
            return np.full(len(points), -1, np.int64)
        x = points[:, 0:1]
        z = points[:, 1:2]
        start_z, end_z = self.start[:, 1], self.end[:, 1]
        crosses = (start_z > z) != (end_z > z)
        dz = np.where(crosses, end_z - start_z, 1.0)
        x_cross = self.start[:, 0] + (z - start_z) * (self.end[:, 0] - self.start[:, 0]) / dz
        hits = (crosses & (x < x_cross)).astype(np.int32)
        inside = np.add.reduceat(hits, self.first_edge, axis=1) % 2 == 1
        first = inside.argmax(axis=1)
        found = inside[np.arange(len(points)), first]
        return np.where(found, self.room_ids[first], -1)

    def nearest_room(self, x: float, z: float) -> int:
        """The id of the room whose outline passes nearest the point (the first on a tie)."""
        edge = self.end - self.start
        offset = np.array([x, z]) - self.start
        length2 = np.maximum(np.sum(edge * edge, axis=1), 1e-18)
        t = np.clip(np.sum(offset * edge, axis=1) / length2, 0.0, 1.0)
        gaps = np.linalg.norm(offset - t[:, None] * edge, axis=1)
        return int(self.room_ids[int(np.argmin(np.minimum.reduceat(gaps, self.first_edge)))])


@dataclass(frozen=True)
class HouseIndex:
    """Look-ups over one house: which room a point is in, instances, relations, landmarks."""

    house: House
    instances: dict[int, ObjectInstance]
    relations: dict[int, list[Relation]]  # by subject id, nearest first
    relations_to: dict[int, list[Relation]]  # by object id, nearest first
    category_pattern: re.Pattern[str]  # finds category names, aliases (or plurals) in text
    landmarks: dict[int, list[ObjectInstance]]  # by room id
    _storey_edges: dict[int | None, _RoomEdges]  # None: every room; by level if several
    _storey_floors: dict[int, float]  # floor height by storey level

    @staticmethod
    def build(house: House) -> HouseIndex:
        relations: dict[int, list[Relation]] = {}
        relations_to: dict[int, list[Relation]] = {}
        for relation in sorted(house.relations, key=lambda r: (r.distance, r.subject, r.object)):
            relations.setdefault(relation.subject, []).append(relation)
            relations_to.setdefault(relation.object, []).append(relation)
        floors = {room.id: room.floor_y for room in house.rooms}
        landmarks: dict[int, list[ObjectInstance]] = {}
        for inst in house.instances:
            if _is_landmark(inst, floors.get(inst.room_id, 0.0)):
                landmarks.setdefault(inst.room_id, []).append(inst)
        storey_edges: dict[int | None, _RoomEdges] = {None: _RoomEdges.of(list(house.rooms))}
        levels = {room.level for room in house.rooms}
        for level in levels if len(levels) > 1 else ():  # one storey: storey_at gives None
            storey_edges[level] = _RoomEdges.of([r for r in house.rooms if r.level == level])
        return HouseIndex(
            house,
            {inst.id: inst for inst in house.instances},
            relations,
            relations_to,
            _category_pattern({inst.category for inst in house.instances}),
            landmarks,
            storey_edges,
            {room.level: room.floor_y for room in house.rooms},
        )

    def storey_at(self, y: float | None) -> int | None:
        """The storey whose floor is nearest the height; None in a one-storey house (or
        without a height), where every room is on the one storey."""
        floors = self._storey_floors
        if y is None or len(floors) < 2:
            return None
        return min(floors, key=lambda level: (abs(floors[level] - y), level))

    def rooms_at(self, points: NDArray[np.float64], y: float | None = None) -> NDArray[np.int64]:
        """Room id of each floor-plan point ``(n, 2)``; -1 where no room contains it. With
        several storeys, ``y`` (the height) picks the storey's rooms."""
        return self._storey_edges[self.storey_at(y)].first_room_containing(points)

    def room_at(self, x: float, z: float, y: float | None = None) -> Room | None:
        """The room containing the point or, for a point in a wall or doorway, the nearest
        (on the storey of height ``y`` when the house has several)."""
        edges = self._storey_edges[self.storey_at(y)]
        if not len(edges.room_ids):
            return None
        room_id = int(edges.first_room_containing(np.array([[x, z]]))[0])
        return self.house.room(room_id if room_id >= 0 else edges.nearest_room(x, z))

    def room_of(self, instance: ObjectInstance) -> Room | None:
        """The room an instance is in: its own, else the room its box stands in (on the
        storey of the box's foot)."""
        try:
            return self.house.room(instance.room_id)
        except KeyError:
            x, _, z = instance.box.center
            return self.room_at(x, z, instance.box.min[1])

    def same_type_rooms(self, room: Room) -> int:
        return sum(1 for other in self.house.rooms if other.type == room.type)


def _category_pattern(categories: set[str]) -> re.Pattern[str]:
    """Finds the categories and their aliases ("sofa" for a couch); map a match with
    :func:`~vlln.world.catalogue.aliases.canonical_category`."""
    words = categories | set(aliases_of(categories))
    names = "|".join(
        re.escape(c) + (_AUXILIARY_USE if c in _AUXILIARY_NAMES else "")
        for c in sorted(words, key=len, reverse=True)
    )
    return re.compile(rf"\b({names})s?\b" if names else r"(?!)")


def _is_landmark(inst: ObjectInstance, floor_y: float) -> bool:
    if any(word in inst.category for word in _NOT_LANDMARK_WORDS):
        return False
    return max(inst.box.size) >= LANDMARK_MIN_SIZE and (
        inst.box.min[1] - floor_y <= LANDMARK_MAX_HEIGHT
    )


@dataclass
class EpisodeKnowledge:
    """Everything one episode's answers read: the house, the target and the way to it."""

    index: HouseIndex
    target: ObjectInstance
    field: GeodesicField | StoreyField
    follower: GreedyFollower
    rng: np.random.Generator

    @staticmethod
    def for_episode(
        context: EpisodeContext, index: HouseIndex, seed: int, goal_radius: float
    ) -> EpisodeKnowledge:
        """Build the episode's look-ups once; paraphrases are seeded by (seed, house, target)
        so the same seed and episode give the same words."""
        simulator = context.simulator
        field = simulator.distance_field(context.view_points)
        follower = GreedyFollower(simulator.nav, field, goal_radius, simulator.config.motion)
        entropy = [seed, zlib.crc32(index.house.name.encode("utf-8")), context.target.id]
        return EpisodeKnowledge(
            index=index,
            target=context.target,
            field=field,
            follower=follower,
            rng=np.random.default_rng(np.random.SeedSequence(entropy)),
        )

    @property
    def target_room(self) -> Room | None:
        return self.index.room_of(self.target)

    def plan_distance(self, x: float, z: float) -> float:
        """Floor-plan distance from a point to the target's box (0 inside its footprint)."""
        return self.target.box.plan_distance(x, z)

    def geodesic(self, x: float, z: float, y: float | None = None) -> float:
        """Walking distance to the nearest view point; ``inf`` when it cannot be reached
        (``y``, the height, is needed in a house with several storeys)."""
        return self.field.distance(x, z, y)
