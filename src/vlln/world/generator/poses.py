"""Candidate poses for one object: where it could go given how it is placed.

Every pose turns the model by a multiple of 90° about +y (walls and tables are axis-aligned, so
fronts face straight into rooms and at tables) and moves it; the model's bounds in its local
frame give the world box the object would occupy. The generators here only propose poses;
:class:`vlln.world.generator.room_space.RoomSpace` decides which ones are acceptable.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from vlln.world.generator.rect import Rect
from vlln.world.generator.room_space import WALL_GAP
from vlln.world.model import Box3, Point3

CHAIR_GAP = 0.03  # m between a seat's front and the table edge
CEILING_GAP = 0.001  # m between a ceiling object and the ceiling

# The four walls of a room, as (name, turns that make a model's front face into the room).
# A model's front is local +z; after t quarter turns it faces (sin, cos) of t * 90°.
WALL_SIDES: tuple[tuple[str, int], ...] = (("z0", 0), ("x1", 3), ("z1", 2), ("x0", 1))
SIDE_FACING = {turns: side for side, turns in WALL_SIDES}  # the wall behind a turned model


@dataclass(frozen=True)
class LocalBounds:
    """A model's axis-aligned bounds in its own frame."""

    lo: Point3
    hi: Point3

    def turned(self, turns: int) -> tuple[float, float, float, float]:
        """``(x0, x1, z0, z1)`` of the bounds after ``turns`` quarter turns about +y."""
        (x0, _, z0), (x1, _, z1) = self.lo, self.hi
        return (
            (x0, x1, z0, z1),
            (z0, z1, -x1, -x0),
            (-x1, -x0, -z1, -z0),
            (-z1, -z0, x0, x1),
        )[turns % 4]

    @property
    def height(self) -> float:
        return self.hi[1] - self.lo[1]


@dataclass(frozen=True)
class Pose:
    """``turns`` quarter turns about +y, then a move by ``offset``."""

    turns: int
    offset: Point3

    @property
    def yaw(self) -> float:
        return (0.0, math.pi / 2.0, math.pi, -math.pi / 2.0)[self.turns % 4]

    def box(self, bounds: LocalBounds) -> Box3:
        x0, x1, z0, z1 = bounds.turned(self.turns)
        ox, oy, oz = self.offset
        return Box3((x0 + ox, bounds.lo[1] + oy, z0 + oz), (x1 + ox, bounds.hi[1] + oy, z1 + oz))


def against_wall(
    interior: Rect, bounds: LocalBounds, rng: np.random.Generator, tries: int, y: float = 0.0
) -> Iterator[tuple[str, Pose]]:
    """Backs to a wall at random places along the walls, longer walls more often."""
    lengths = np.array([_side_length(interior, side) for side, _ in WALL_SIDES])
    for _ in range(tries):
        k = int(rng.choice(4, p=lengths / lengths.sum()))
        side, turns = WALL_SIDES[k]
        span = _slide_range(interior, side, bounds.turned(turns))
        if span is None:
            continue
        fixed, lo, hi = span
        yield side, _pose(side, turns, fixed, float(rng.uniform(lo, hi)), y)


def centred_on_wall(
    interior: Rect, bounds: LocalBounds, rng: np.random.Generator
) -> Iterator[tuple[str, Pose]]:
    """Backs to the middle of each wall (a bed's head), in random order, slightly off centre."""
    for k in rng.permutation(4):
        side, turns = WALL_SIDES[int(k)]
        span = _slide_range(interior, side, bounds.turned(turns))
        if span is None:
            continue
        fixed, lo, hi = span
        along = (lo + hi) / 2.0 + float(rng.normal(0.0, 0.15)) * (hi - lo)
        yield side, _pose(side, turns, fixed, float(np.clip(along, lo, hi)), 0.0)


def in_corners(
    interior: Rect, bounds: LocalBounds, rng: np.random.Generator
) -> Iterator[tuple[str, Pose]]:
    """Back to one wall and a side to the other, in each corner, in random order."""
    for k in rng.permutation(8):
        side, turns = WALL_SIDES[int(k) // 2]
        span = _slide_range(interior, side, bounds.turned(turns))
        if span is None:
            continue
        fixed, lo, hi = span
        yield side, _pose(side, turns, fixed, lo if k % 2 == 0 else hi, 0.0)


def free_standing(
    interior: Rect, bounds: LocalBounds, rng: np.random.Generator, tries: int
) -> Iterator[Pose]:
    """Aligned with the room's long axis, near the middle of the room at first."""
    lx = bounds.hi[0] - bounds.lo[0]
    lz = bounds.hi[2] - bounds.lo[2]
    along_x = (lx >= lz) == (interior.width >= interior.depth)
    for attempt in range(tries):
        turns = (0 if along_x else 1) + 2 * int(rng.integers(2))
        x0, x1, z0, z1 = bounds.turned(turns)
        spread = 0.15 + 0.1 * attempt  # wander further from the middle after failures
        cx = (interior.x0 + interior.x1) / 2.0 + float(rng.normal(0.0, spread)) * interior.width
        cz = (interior.z0 + interior.z1) / 2.0 + float(rng.normal(0.0, spread)) * interior.depth
        ox = float(np.clip(cx - (x0 + x1) / 2.0, interior.x0 - x0, interior.x1 - x1))
        oz = float(np.clip(cz - (z0 + z1) / 2.0, interior.z0 - z0, interior.z1 - z1))
        yield Pose(turns, (ox, 0.0, oz))


def around_table(table: Rect, bounds: LocalBounds, rng: np.random.Generator) -> list[Pose]:
    """Seats facing a table from each of its sides, evenly spaced along each side."""
    poses = []
    # (turns that face the table from this side, along x?, table edge, outward sign)
    for turns, along_x, edge, sign in (
        (2, True, table.z1, 1.0),
        (0, True, table.z0, -1.0),
        (3, False, table.x1, 1.0),
        (1, False, table.x0, -1.0),
    ):
        x0, x1, z0, z1 = bounds.turned(turns)
        width = x1 - x0 if along_x else z1 - z0
        side = table.width if along_x else table.depth
        if side < 0.8 * width:
            continue
        n = max(1, math.floor((side + 0.1) / (width + 0.1)))
        start = table.x0 if along_x else table.z0
        for i in range(n):
            centre = start + (i + 0.5) * side / n
            if along_x:
                oz = edge + CHAIR_GAP - z0 if sign > 0 else edge - CHAIR_GAP - z1
                poses.append(Pose(turns, (centre - (x0 + x1) / 2.0, 0.0, oz)))
            else:
                ox = edge + CHAIR_GAP - x0 if sign > 0 else edge - CHAIR_GAP - x1
                poses.append(Pose(turns, (ox, 0.0, centre - (z0 + z1) / 2.0)))
    return [poses[int(i)] for i in rng.permutation(len(poses))]


def under_ceiling(
    interior: Rect, bounds: LocalBounds, ceiling: float, rng: np.random.Generator, tries: int
) -> Iterator[Pose]:
    """Hanging from the ceiling: the middle of the room first, then anywhere."""
    x0, x1, z0, z1 = bounds.turned(0)
    y = ceiling - CEILING_GAP - bounds.hi[1]
    for attempt in range(tries):
        u, v = (0.5, 0.5) if attempt == 0 else (float(rng.uniform()), float(rng.uniform()))
        ox = interior.x0 - x0 + u * (interior.width - (x1 - x0))
        oz = interior.z0 - z0 + v * (interior.depth - (z1 - z0))
        yield Pose(0, (ox, y, oz))


def beside(interior: Rect, bounds: LocalBounds, side: str, anchor: Box3, gap: float) -> list[Pose]:
    """Back to the same wall as ``anchor`` (which stands against ``side``), left and right."""
    turns = dict(WALL_SIDES)[side]
    span = _slide_range(interior, side, bounds.turned(turns))
    if span is None:
        return []
    fixed, lo, hi = span
    x0, x1, z0, z1 = bounds.turned(turns)
    if side in ("z0", "z1"):
        alongs = (anchor.min[0] - gap - x1, anchor.max[0] + gap - x0)
    else:
        alongs = (anchor.min[2] - gap - z1, anchor.max[2] + gap - z0)
    return [_pose(side, turns, fixed, a, 0.0) for a in alongs if lo <= a <= hi]


def in_front_of(bounds: LocalBounds, side: str, anchor: Box3, gap: float) -> Pose:
    """Centred in front of ``anchor`` (against ``side``), ``gap`` from its front, same turn."""
    turns = dict(WALL_SIDES)[side]
    x0, x1, z0, z1 = bounds.turned(turns)
    if side in ("z0", "z1"):
        ox = (anchor.min[0] + anchor.max[0]) / 2.0 - (x0 + x1) / 2.0
        oz = anchor.max[2] + gap - z0 if side == "z0" else anchor.min[2] - gap - z1
    else:
        oz = (anchor.min[2] + anchor.max[2]) / 2.0 - (z0 + z1) / 2.0
        ox = anchor.max[0] + gap - x0 if side == "x0" else anchor.min[0] - gap - x1
    return Pose(turns, (ox, 0.0, oz))


def across_from(interior: Rect, bounds: LocalBounds, side: str, anchor: Box3) -> list[Pose]:
    """Back to the wall opposite ``side``, facing ``anchor`` across the room."""
    opposite = {"z0": "z1", "z1": "z0", "x0": "x1", "x1": "x0"}[side]
    pose = _on_wall_centred_on(interior, bounds, opposite, anchor, 0.0)
    return [] if pose is None else [pose]


def above(
    interior: Rect, bounds: LocalBounds, side: str, anchor: Box3, y: float
) -> list[tuple[str, Pose]]:
    """On the wall behind ``anchor`` (which stands against ``side``), centred over it at
    height ``y``: a range hood over the stove."""
    pose = _on_wall_centred_on(interior, bounds, side, anchor, y)
    return [] if pose is None else [(side, pose)]


def _on_wall_centred_on(
    interior: Rect, bounds: LocalBounds, wall: str, anchor: Box3, y: float
) -> Pose | None:
    """Back to ``wall`` at height ``y``, slid along it to ``anchor``'s centre as far as the
    wall allows; None when the object does not fit along the wall."""
    turns = dict(WALL_SIDES)[wall]
    x0, x1, z0, z1 = bounds.turned(turns)
    span = _slide_range(interior, wall, (x0, x1, z0, z1))
    if span is None:
        return None
    fixed, lo, hi = span
    if wall in ("z0", "z1"):
        along = (anchor.min[0] + anchor.max[0]) / 2.0 - (x0 + x1) / 2.0
    else:
        along = (anchor.min[2] + anchor.max[2]) / 2.0 - (z0 + z1) / 2.0
    return _pose(wall, turns, fixed, float(np.clip(along, lo, hi)), y)


def wall_line(room: Rect, side: str) -> tuple[str, float]:
    """The wall line ``(axis, coord)`` of a room side, as used by doors."""
    return {
        "z0": ("x", room.z0),
        "z1": ("x", room.z1),
        "x0": ("z", room.x0),
        "x1": ("z", room.x1),
    }[side]


def _side_length(interior: Rect, side: str) -> float:
    return interior.width if side in ("z0", "z1") else interior.depth


def _slide_range(
    interior: Rect, side: str, extent: tuple[float, float, float, float]
) -> tuple[float, float, float] | None:
    """The fixed offset that puts the back on this wall, and the offsets along the wall."""
    x0, x1, z0, z1 = extent
    if side in ("z0", "z1"):
        fixed = interior.z0 + WALL_GAP - z0 if side == "z0" else interior.z1 - WALL_GAP - z1
        lo, hi = interior.x0 + WALL_GAP - x0, interior.x1 - WALL_GAP - x1
    else:
        fixed = interior.x0 + WALL_GAP - x0 if side == "x0" else interior.x1 - WALL_GAP - x1
        lo, hi = interior.z0 + WALL_GAP - z0, interior.z1 - WALL_GAP - z1
    return (fixed, lo, hi) if hi >= lo else None


def _pose(side: str, turns: int, fixed: float, along: float, y: float) -> Pose:
    if side in ("z0", "z1"):
        return Pose(turns, (along, y, fixed))
    return Pose(turns, (fixed, y, along))
