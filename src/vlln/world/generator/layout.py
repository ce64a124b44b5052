"""Floor plans: which rooms a house has, where their walls are and where the doors go.

A plan is drawn in three steps. A *programme* lists the room types (a living room, a kitchen
and a bathroom first, then bedrooms, a dining room, a toilet, ...), each with a target share of
the floor. The rooms are then laid out as axis-aligned rectangles: small houses split one
rectangle recursively (a treemap whose cuts follow the target shares), larger houses put the
living rooms in one block and the private rooms on both sides of a corridor in another, which
gives a rectangular or L-shaped footprint. Finally :mod:`~vlln.world.generator.doors` joins
the rooms with doors so that every room is reachable.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vlln.errors import HouseParametersError
from vlln.world.generator.doors import place_doors
from vlln.world.generator.params import (
    DOOR_CORNER_MARGIN,
    MAX_AREA_PER_ROOM,
    MIN_AREA_PER_ROOM,
    MIN_ROOM_SIDE,
    HouseParameters,
)
from vlln.world.generator.rect import Rect
from vlln.world.model import Door, Room

# Target floor share of each room type, relative to a living room.
ROOM_WEIGHT: dict[str, float] = {
    "living room": 1.0,
    "kitchen": 0.55,
    "dining room": 0.6,
    "bedroom": 0.75,
    "bathroom": 0.3,
    "toilet": 0.17,
    "study": 0.45,
    "storage room": 0.2,
    "gym": 0.6,
}
PUBLIC_ROOMS = ("living room", "dining room", "kitchen")
# Rooms added after the core (living room, kitchen, bathroom, bedroom), in order of priority.
EXTRA_ROOMS = (
    "bedroom",
    "dining room",
    "toilet",
    "study",
    "bedroom",
    "storage room",
    "bathroom",
    "gym",
    "bedroom",
    "study",
    "storage room",
)
CORRIDOR_MIN_ROOMS = 7  # houses with this many rooms get a corridor
_LAYOUT_ATTEMPTS = 60


@dataclass
class FloorPlan:
    """Rooms (rectangles, ids 0..n-1 in list order) and the doors between them."""

    rooms: list[Room]
    doors: list[Door]

    @property
    def rects(self) -> list[Rect]:
        return [Rect.of_room(room) for room in self.rooms]

    @property
    def area(self) -> float:
        return sum(rect.area for rect in self.rects)


def plan_floor(params: HouseParameters, rng: np.random.Generator) -> FloorPlan:
    """Draw a floor plan that satisfies ``params`` (call ``params.validate()`` first)."""
    low = max(params.min_area, params.min_rooms * MIN_AREA_PER_ROOM)
    high = min(params.max_area, params.max_rooms * MAX_AREA_PER_ROOM)
    for _ in range(_LAYOUT_ATTEMPTS):
        area = float(rng.uniform(low, high))
        fewest = max(params.min_rooms, math.ceil(area / MAX_AREA_PER_ROOM))
        most = min(params.max_rooms, math.floor(area / MIN_AREA_PER_ROOM))
        n_rooms = int(np.clip(round(area / rng.uniform(14.0, 24.0)), fewest, most))
        types = room_programme(n_rooms, rng)
        rects = _lay_out(types, area, params, rng)
        if rects is None:
            continue
        rects = _reorient(rects, rng)
        rooms = [
            Room(i, kind, rect.polygon, 0.0, params.ceiling_height)
            for i, (kind, rect) in enumerate(zip(types, rects, strict=True))
        ]
        doors = place_doors(rooms, rects, params, rng)
        if doors is not None:
            return FloorPlan(rooms, doors)
    raise HouseParametersError(
        f"no floor plan found for {params}; widen the room or area ranges "
        f"(e.g. raise max_area or lower min_rooms)"
    )


def room_programme(n_rooms: int, rng: np.random.Generator) -> list[str]:
    """The room types of a house with ``n_rooms`` rooms, living rooms first."""
    core = ["living room", "kitchen", "bathroom", "bedroom"]
    if n_rooms <= len(core):
        return core[:n_rooms]
    extras = list(EXTRA_ROOMS)
    for i in range(len(extras) - 1):  # a few neighbour swaps vary the mix of extra rooms
        if rng.random() < 0.3:
            extras[i], extras[i + 1] = extras[i + 1], extras[i]
    has_corridor = n_rooms >= CORRIDOR_MIN_ROOMS
    n_extra = n_rooms - len(core) - int(has_corridor)
    cycle = ("bedroom", "bathroom", "study", "storage room")
    chosen = extras[:n_extra] + [cycle[i % len(cycle)] for i in range(n_extra - len(extras))]
    return core + chosen + (["corridor"] if has_corridor else [])


def _lay_out(
    types: list[str], area: float, params: HouseParameters, rng: np.random.Generator
) -> list[Rect] | None:
    weights = [ROOM_WEIGHT.get(kind, 0.5) * float(rng.uniform(0.85, 1.15)) for kind in types]
    if "corridor" in types:
        return _corridor_layout(types, weights, area, params, rng)
    aspect = float(rng.uniform(1.0, 1.6))
    width = math.sqrt(area * aspect)
    order = _public_first_order(types)
    placed = _treemap(Rect(0.0, 0.0, width, area / width), [(i, weights[i]) for i in order], rng)
    if placed is None:
        return None
    return [placed[i] for i in range(len(types))]


def _public_first_order(types: list[str]) -> list[int]:
    """Living room, dining room, kitchen, then the rest: neighbours in the list share walls."""
    rank = {kind: k for k, kind in enumerate(PUBLIC_ROOMS)}
    return sorted(range(len(types)), key=lambda i: (rank.get(types[i], len(rank)), i))


def _treemap(
    rect: Rect, items: list[tuple[int, float]], rng: np.random.Generator
) -> dict[int, Rect] | None:
    """Split ``rect`` into one rectangle per item with areas close to the item weights."""
    if len(items) == 1:
        if min(rect.width, rect.depth) < MIN_ROOM_SIDE - 1e-9:
            return None
        return {items[0][0]: rect}
    total = sum(w for _, w in items)
    cumulative = np.cumsum([w for _, w in items])[:-1] / total
    # Cut the item list where the two halves are most balanced, with a little randomness.
    balance = np.abs(cumulative - 0.5) + rng.uniform(0.0, 0.1, len(cumulative))
    cut = int(np.argmin(balance)) + 1
    share = float(cumulative[cut - 1])
    along_x = rect.width >= rect.depth
    length = rect.width if along_x else rect.depth
    if length < 2.0 * MIN_ROOM_SIDE:
        return None
    split = float(np.clip(share * length, MIN_ROOM_SIDE, length - MIN_ROOM_SIDE))
    if along_x:
        first = Rect(rect.x0, rect.z0, rect.x0 + split, rect.z1)
        second = Rect(rect.x0 + split, rect.z0, rect.x1, rect.z1)
    else:
        first = Rect(rect.x0, rect.z0, rect.x1, rect.z0 + split)
        second = Rect(rect.x0, rect.z0 + split, rect.x1, rect.z1)
    a = _treemap(first, items[:cut], rng)
    b = _treemap(second, items[cut:], rng)
    if a is None or b is None:
        return None
    return a | b


def _corridor_layout(
    types: list[str],
    weights: list[float],
    area: float,
    params: HouseParameters,
    rng: np.random.Generator,
) -> list[Rect] | None:
    """Living rooms in one block; private rooms along both sides of a corridor in another."""
    public = [i for i, kind in enumerate(types) if kind in PUBLIC_ROOMS]
    private = [i for i, kind in enumerate(types) if kind not in PUBLIC_ROOMS and kind != "corridor"]
    corridor = types.index("corridor")
    strips: tuple[list[int], list[int]] = ([], [])
    for i in sorted(private, key=lambda i: -weights[i]):  # balance the two strips by weight
        lighter = min((0, 1), key=lambda s: sum(weights[j] for j in strips[s]))
        strips[lighter].append(i)
    for strip in strips:
        rng.shuffle(strip)
    corridor_width = max(
        params.door_width + 2.0 * DOOR_CORNER_MARGIN + params.wall_thickness + 0.05,
        float(rng.uniform(MIN_ROOM_SIDE, 1.9)),
    )
    w_public = sum(weights[i] for i in public)
    w_private = sum(weights[i] for i in private)
    # Strips deep enough that the house is not much longer than it is deep.
    target_depth = (math.sqrt(area / rng.uniform(1.2, 1.8)) - corridor_width) / 2.0
    first_depth = float(np.clip(target_depth, 3.0, 4.8))
    # The heavier strip (more or larger rooms) gets the deeper side of the corridor.
    strip_weights = [sum(weights[i] for i in strip) for strip in strips]
    share = float(np.clip(strip_weights[0] / sum(strip_weights), 0.35, 0.65))
    for strip_depth in np.linspace(first_depth, 2.4, 8):
        depths = (
            max(MIN_ROOM_SIDE, float(2.0 * strip_depth * share)),
            max(MIN_ROOM_SIDE, float(2.0 * strip_depth * (1.0 - share))),
        )
        block_depth = depths[0] + corridor_width + depths[1]
        length = area / (block_depth + (depths[0] + depths[1]) * w_public / w_private)
        if all(len(s) * MIN_ROOM_SIDE <= length for s in strips):
            break
    else:
        return None
    public_area = area - block_depth * length
    public_depth = block_depth
    if rng.random() < 0.6:  # an L-shaped footprint
        public_depth *= float(rng.uniform(0.75, 1.3))
    reach = depths[0] + corridor_width  # the corridor's far side, measured from z = 0
    top_aligned = rng.random() < 0.5
    z0 = 0.0 if top_aligned else block_depth - public_depth
    # The corridor's end wall must open onto the public block.
    if z0 > depths[0] or z0 + public_depth < reach:
        z0, public_depth = 0.0, block_depth
    public_length = public_area / public_depth
    if public_length < MIN_ROOM_SIDE:
        return None
    block = Rect(0.0, z0, public_length, z0 + public_depth)
    placed = _treemap(
        block, [(i, weights[i]) for i in _public_first_order(types) if i in public], rng
    )
    if placed is None:
        return None
    x = public_length
    placed[corridor] = Rect(x, depths[0], x + length, reach)
    for strip, (za, zb) in zip(strips, ((0.0, depths[0]), (reach, block_depth)), strict=True):
        widths = _strip_widths([weights[i] for i in strip], length)
        edges = np.concatenate([[0.0], np.cumsum(widths)])
        for i, a, b in zip(strip, edges[:-1], edges[1:], strict=True):
            placed[i] = Rect(x + float(a), za, x + float(b), zb)
    return [placed[i] for i in range(len(types))]


def _strip_widths(weights: list[float], length: float) -> list[float]:
    """Widths along a strip proportional to the weights, none below the minimum room side."""
    widths = np.array(weights) / sum(weights) * length
    fixed = np.zeros(len(widths), bool)
    while True:
        small = ~fixed & (widths < MIN_ROOM_SIDE)
        if not small.any():
            break
        fixed |= small
        widths[fixed] = MIN_ROOM_SIDE
        free_length = length - MIN_ROOM_SIDE * fixed.sum()
        if fixed.all() or free_length <= 0.0:
            break
        widths[~fixed] *= free_length / widths[~fixed].sum()
    widths[-1] = length - widths[:-1].sum()
    return [float(w) for w in widths]


def _reorient(rects: list[Rect], rng: np.random.Generator) -> list[Rect]:
    """Mirror and turn the plan at random and move its corner to the origin.

    Walls that two rooms share are computed from the same numbers on both sides, so they
    compare exactly equal here as well.
    """
    flip_x, flip_z, swap = (bool(rng.random() < 0.5) for _ in range(3))
    out = []
    for r in rects:
        x0, z0, x1, z1 = r.x0, r.z0, r.x1, r.z1
        if flip_x:
            x0, x1 = -x1, -x0
        if flip_z:
            z0, z1 = -z1, -z0
        if swap:
            x0, z0, x1, z1 = z0, x0, z1, x1
        out.append((x0, z0, x1, z1))
    min_x = min(r[0] for r in out)
    min_z = min(r[1] for r in out)
    return [Rect(a - min_x, b - min_z, c - min_x, d - min_z) for a, b, c, d in out]
