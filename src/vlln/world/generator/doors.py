"""Doors between rooms: which rooms share a wall, and where the doors in those walls go.

Doors follow a spanning tree of the adjacency graph so that every room is reachable. Rooms one
only enters to use (bathrooms, toilets, storage rooms) are leaves of that tree, so no one has
to walk through a bathroom; corridor and living-area doors are preferred, and a few extra
doors open up the living area.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vlln.world.generator.params import DOOR_CORNER_MARGIN, HouseParameters
from vlln.world.generator.rect import Rect
from vlln.world.model import Door, Room

OPEN_PLAN_ROOMS = ("living room", "dining room", "kitchen", "corridor")
DEAD_END_ROOMS = ("bathroom", "toilet", "storage room")
MAX_EXTRA_DOORS = 3


@dataclass(frozen=True)
class SharedWall:
    """The stretch of wall two rooms have in common: on line ``axis_coord`` along ``axis``."""

    room_a: int
    room_b: int
    axis: str  # the wall runs along "x" (constant z) or "z" (constant x)
    coord: float  # the constant coordinate of the wall line
    start: float
    end: float

    @property
    def length(self) -> float:
        return self.end - self.start


def shared_walls(rects: list[Rect]) -> list[SharedWall]:
    """Every stretch of wall that two rooms have in common, with positive length."""
    walls = []
    for a in range(len(rects)):
        for b in range(a + 1, len(rects)):
            ra, rb = rects[a], rects[b]
            for coord_a, coord_b, axis in (
                (ra.x1, rb.x0, "z"),
                (ra.x0, rb.x1, "z"),
                (ra.z1, rb.z0, "x"),
                (ra.z0, rb.z1, "x"),
            ):
                if coord_a != coord_b:
                    continue
                if axis == "z":
                    start, end = max(ra.z0, rb.z0), min(ra.z1, rb.z1)
                else:
                    start, end = max(ra.x0, rb.x0), min(ra.x1, rb.x1)
                if end > start:
                    walls.append(SharedWall(a, b, axis, coord_a, start, end))
    return walls


def outer_sides(rects: list[Rect]) -> list[set[str]]:
    """Per room, the sides (``"x0"``, ``"x1"``, ``"z0"``, ``"z1"``) it shares with no room."""
    shared: list[set[str]] = [set() for _ in rects]
    for wall in shared_walls(rects):
        for i in (wall.room_a, wall.room_b):
            r = rects[i]
            if wall.axis == "z":
                shared[i].add("x0" if wall.coord == r.x0 else "x1")
            else:
                shared[i].add("z0" if wall.coord == r.z0 else "z1")
    return [{"x0", "x1", "z0", "z1"} - s for s in shared]


# How much a door between two room types is wanted (lower is better) when joining rooms.
def _door_cost(kind_a: str, kind_b: str) -> float:
    pair = {kind_a, kind_b}
    if "corridor" in pair:
        return 0.0
    if pair == {"kitchen", "dining room"}:
        return 0.1
    if "living room" in pair and pair & {"dining room", "kitchen"}:
        return 0.2
    if pair & {"bathroom", "toilet", "storage room"}:
        return 1.5 if pair & {"bedroom", "living room"} else 3.0
    if "living room" in pair:
        return 1.0
    return 2.0


def place_doors(
    rooms: list[Room], rects: list[Rect], params: HouseParameters, rng: np.random.Generator
) -> list[Door] | None:
    """Doors on a spanning tree of the adjacency graph plus a few extras; None if disconnected."""
    margin = DOOR_CORNER_MARGIN + params.wall_thickness / 2.0 + params.door_width / 2.0
    candidates = [w for w in shared_walls(rects) if w.length >= 2.0 * margin]
    costs = [
        _door_cost(rooms[w.room_a].type, rooms[w.room_b].type) + float(rng.uniform(0.0, 0.5))
        for w in candidates
    ]
    order = sorted(range(len(candidates)), key=lambda k: (costs[k], k))
    parent = list(range(len(rooms)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    # Rooms one only enters to use (bathrooms, ...) are leaves: no one walks through them.
    is_leaf = [room.type in DEAD_END_ROOMS for room in rooms]
    chosen: list[SharedWall] = []
    left_over: list[SharedWall] = []
    for k in order:  # Kruskal over the rooms one may pass through
        wall = candidates[k]
        if is_leaf[wall.room_a] or is_leaf[wall.room_b]:
            continue
        ra, rb = root(wall.room_a), root(wall.room_b)
        if ra != rb:
            parent[ra] = rb
            chosen.append(wall)
        else:
            left_over.append(wall)
    attached: set[int] = set()
    for k in order:  # then each dead-end room hangs off its cheapest neighbour
        wall = candidates[k]
        if is_leaf[wall.room_a] == is_leaf[wall.room_b]:
            continue
        leaf, other = (
            (wall.room_a, wall.room_b) if is_leaf[wall.room_a] else (wall.room_b, wall.room_a)
        )
        if leaf not in attached:
            attached.add(leaf)
            parent[leaf] = root(other)
            chosen.append(wall)
    if len({root(i) for i in range(len(rooms))}) > 1:
        return None
    open_plan = set(OPEN_PLAN_ROOMS)
    extras = 0
    for wall in left_over:
        kinds = {rooms[wall.room_a].type, rooms[wall.room_b].type}
        if extras < MAX_EXTRA_DOORS and kinds <= open_plan and rng.random() < 0.5:
            chosen.append(wall)
            extras += 1
    doors = []
    for door_id, wall in enumerate(sorted(chosen, key=lambda w: (w.room_a, w.room_b))):
        low, high = wall.start + margin, wall.end - margin
        # Doors near a corner leave long stretches of wall for furniture.
        if rng.random() < 0.6:
            near_start = rng.random() < 0.5
            span = 0.25 * (high - low)
            pos = (
                low + float(rng.uniform(0, span))
                if near_start
                else high - float(rng.uniform(0, span))
            )
        else:
            pos = float(rng.uniform(low, high))
        center = (wall.coord, pos) if wall.axis == "z" else (pos, wall.coord)
        doors.append(Door(door_id, wall.room_a, wall.room_b, center, params.door_width, wall.axis))
    return doors


def door_along(door: Door) -> float:
    """Position of a door's centre along its wall."""
    return door.center[0] if door.axis == "x" else door.center[1]


def door_wall_coord(door: Door) -> float:
    """The constant coordinate of the wall line a door is in."""
    return door.center[1] if door.axis == "x" else door.center[0]
