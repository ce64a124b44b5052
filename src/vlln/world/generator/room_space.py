"""The free space of one room while it is being furnished.

A room keeps the footprints of what stands on its floor, the boxes of everything in it, the
clear zones in front of its doors, and a coarse occupancy grid. A candidate placement is
accepted only if it stays inside the walls, overlaps nothing, keeps the door zones clear and
leaves the free floor walkable: obstacles (including things hung on a wall below the agent's
height) are inflated by the agent's radius and the grid is labelled into connected
components; one of them must join every door and hold most of the floor, and the others may
only be small nooks.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

from vlln.world.generator.doors import door_along, door_wall_coord
from vlln.world.generator.rect import Rect
from vlln.world.generator.structure import DOOR_HEIGHT
from vlln.world.model import Box3, Door

GRID_CELL = 0.1  # m, the occupancy grid used for the walkability check
AGENT_CLEARANCE = 0.2  # m, obstacles and walls are inflated by this much
DOOR_ZONE_DEPTH = 1.0  # m kept clear in front of every door (from the wall face), both sides
DOOR_ZONE_EXTRA = 0.1  # m added to each side of a door's width for its clear zone
MIN_CONNECTED_SHARE = 0.7  # of the free floor that must stay in the doors' component
MAX_POCKET_AREA = 0.5  # m²; free floor cut off from the doors may only form nooks this small
AGENT_HEIGHT = 1.5  # m; things hanging lower than this are in the way of the agent's body
WALL_GAP = 0.01  # m between furniture and the wall it stands against
# m beyond the walkable edge: the cells in front of a door that must be free and joined up
_MOUTH_DEPTH = (0.05, 0.25)


def rects_overlap(a: Rect, b: Rect, gap: float = 0.0) -> bool:
    """Whether two floor-plan rectangles overlap, or come closer than ``gap``."""
    return a.x0 < b.x1 + gap and b.x0 < a.x1 + gap and a.z0 < b.z1 + gap and b.z0 < a.z1 + gap


def boxes_intersect(a: Box3, b: Box3) -> bool:
    """Whether two boxes overlap with positive volume."""
    return all(a.min[i] < b.max[i] and b.min[i] < a.max[i] for i in range(3))


def footprint(box: Box3) -> Rect:
    """The floor-plan rectangle under a box."""
    return Rect(box.min[0], box.min[2], box.max[0], box.max[2])


@dataclass
class RoomSpace:
    """What is already in a room, and the rules a new object must satisfy."""

    rect: Rect  # the room as drawn on the plan (wall centre lines)
    interior: Rect  # the floor between the wall faces
    ceiling: float
    door_zones: list[Rect]
    door_mouths: list[Rect]
    door_spans: list[tuple[str, float, float, float]]  # (wall axis, wall coord, lo, hi)
    footprints: list[Rect] = field(default_factory=list)  # solid things standing on the floor
    boxes: list[tuple[int, Box3]] = field(default_factory=list)  # (instance id, box)
    _blocked: NDArray[np.bool_] = field(init=False)
    _xs: NDArray[np.float64] = field(init=False)
    _zs: NDArray[np.float64] = field(init=False)
    _mouth_cells: list[tuple[slice, slice]] = field(init=False)
    _cell_area: float = field(init=False)

    def __post_init__(self) -> None:
        # No check: this builds the occupancy grid that the fields above imply.
        inner = self.interior
        nx = max(1, round(inner.width / GRID_CELL))
        nz = max(1, round(inner.depth / GRID_CELL))
        self._xs = inner.x0 + (np.arange(nx) + 0.5) * inner.width / nx
        self._zs = inner.z0 + (np.arange(nz) + 0.5) * inner.depth / nz
        self._blocked = np.zeros((nz, nx), bool)
        walkable = inner.shrunk(AGENT_CLEARANCE)
        self._blocked |= ~self._mask(walkable, 0.0)
        self._mouth_cells = [self._cell_slices(m) for m in self.door_mouths]
        self._cell_area = inner.width / nx * inner.depth / nz

    @staticmethod
    def of_room(
        rect: Rect, ceiling: float, wall_thickness: float, doors: list[Door], room_id: int
    ) -> RoomSpace:
        face = wall_thickness / 2.0
        interior = rect.shrunk(face)
        mouth_near, mouth_far = (face + AGENT_CLEARANCE + d for d in _MOUTH_DEPTH)
        zones, mouths, spans = [], [], []
        for door in doors:
            if room_id not in (door.room_a, door.room_b):
                continue
            along = door_along(door)
            half = door.width / 2.0
            spans.append((door.axis, door_wall_coord(door), along - half, along + half))
            zone_width = half + DOOR_ZONE_EXTRA
            zones.append(_in_front(rect, door, along, zone_width, 0.0, face + DOOR_ZONE_DEPTH))
            mouth_width = half - AGENT_CLEARANCE
            mouths.append(_in_front(rect, door, along, mouth_width, mouth_near, mouth_far))
        return RoomSpace(rect, interior, ceiling, zones, mouths, spans)

    # ---- checks -------------------------------------------------------------------------

    def fits_floor(self, box: Box3) -> bool:
        """An object standing on the floor: inside the walls, clear of doors and others."""
        rect = footprint(box)
        if not self.contains(rect) or box.max[1] > self.ceiling:
            return False
        if any(rects_overlap(rect, zone) for zone in self.door_zones):
            return False
        if any(rects_overlap(rect, other) for other in self.footprints):
            return False
        return not self.intersects_any(box)

    def fits_above_floor(self, box: Box3, ignore: int | None = None, hangs: bool = False) -> bool:
        """An object set on a surface (``ignore`` its support) or hung on a wall or ceiling.

        A hanging object lower than the door lintels keeps out of the doorways, and one low
        enough to meet the agent also keeps the floor clear.
        """
        if not (
            self.contains(footprint(box))
            and box.max[1] <= self.ceiling + 1e-6
            and not self.intersects_any(box, ignore)
        ):
            return False
        if not hangs or box.min[1] >= DOOR_HEIGHT:
            return True
        rect = footprint(box)
        if any(rects_overlap(rect, zone) for zone in self.door_zones):
            return False
        return box.min[1] >= AGENT_HEIGHT or self.keeps_floor_walkable(rect)

    def intersects_any(self, box: Box3, ignore: int | None = None) -> bool:
        return any(boxes_intersect(box, other) for owner, other in self.boxes if owner != ignore)

    def keeps_floor_walkable(self, rect: Rect) -> bool:
        """Whether the doors and most of the free floor stay joined with ``rect`` blocked."""
        blocked = self._blocked | self._mask(rect, AGENT_CLEARANCE)
        return self._walkable(blocked)

    def walls_clear_of_doors(self, axis: str, coord: float, lo: float, hi: float) -> bool:
        """Whether ``[lo, hi]`` along the wall line ``(axis, coord)`` misses every opening."""
        return not any(
            a == axis and abs(c - coord) < 1e-6 and lo < d_hi + 0.05 and d_lo - 0.05 < hi
            for a, c, d_lo, d_hi in self.door_spans
        )

    # ---- updates ------------------------------------------------------------------------

    def add_floor_object(self, instance_id: int, box: Box3) -> None:
        """Something standing on the floor: later objects keep off its footprint."""
        self.boxes.append((instance_id, box))
        rect = footprint(box)
        self.footprints.append(rect)
        self._blocked |= self._mask(rect, AGENT_CLEARANCE)

    def add_object(self, instance_id: int, box: Box3) -> None:
        """Something not standing on the floor; it blocks the agent if it hangs low."""
        self.boxes.append((instance_id, box))
        if box.min[1] < AGENT_HEIGHT:
            self._blocked |= self._mask(footprint(box), AGENT_CLEARANCE)

    # ---- internals ----------------------------------------------------------------------

    def contains(self, rect: Rect) -> bool:
        """Whether a floor-plan rectangle lies between the wall faces."""
        inner = self.interior
        eps = 1e-6
        return (
            rect.x0 >= inner.x0 - eps
            and rect.x1 <= inner.x1 + eps
            and rect.z0 >= inner.z0 - eps
            and rect.z1 <= inner.z1 + eps
        )

    def _cell_slices(self, rect: Rect) -> tuple[slice, slice]:
        i0, i1 = np.searchsorted(self._xs, [rect.x0, rect.x1])
        j0, j1 = np.searchsorted(self._zs, [rect.z0, rect.z1])
        return slice(int(j0), int(j1)), slice(int(i0), int(i1))

    def _mask(self, rect: Rect, inflate: float) -> NDArray[np.bool_]:
        grown = Rect(rect.x0 - inflate, rect.z0 - inflate, rect.x1 + inflate, rect.z1 + inflate)
        mask = np.zeros_like(self._blocked)
        mask[self._cell_slices(grown)] = True
        return mask

    def _walkable(self, blocked: NDArray[np.bool_]) -> bool:
        labels, n = ndimage.label(~blocked)
        if n == 0:
            return False
        component = 0
        for cells in self._mouth_cells:
            found = np.unique(labels[cells])
            if len(found) != 1 or found[0] == 0 or (component and found[0] != component):
                return False  # a door is blocked, or the doors lead to separate pieces
            component = int(found[0])
        sizes = np.bincount(labels.ravel())
        sizes[0] = 0
        if component == 0:
            component = int(np.argmax(sizes))
        pockets = np.delete(sizes, [0, component])
        if pockets.size and pockets.max() * self._cell_area > MAX_POCKET_AREA:
            return False
        return bool(sizes[component] >= MIN_CONNECTED_SHARE * sizes.sum())


def _in_front(
    rect: Rect, door: Door, along: float, half_width: float, near: float, far: float
) -> Rect:
    """The part of ``rect`` in front of a door, ``near..far`` metres from its wall line."""
    if door.axis == "x":  # the wall has constant z: the room lies above or below it
        z = door.center[1]
        if abs(z - rect.z0) < abs(z - rect.z1):
            return Rect(along - half_width, z + near, along + half_width, z + far)
        return Rect(along - half_width, z - far, along + half_width, z - near)
    x = door.center[0]
    if abs(x - rect.x0) < abs(x - rect.x1):
        return Rect(x + near, along - half_width, x + far, along + half_width)
    return Rect(x - far, along - half_width, x - near, along + half_width)
