"""Placing the contents of each room (see :mod:`~vlln.world.generator.contents`).

Objects are placed in phases so that what others depend on exists first: free-standing
furniture (tables, islands), furniture against the walls, corner pieces, seats at the tables,
rugs, things on the walls and the ceiling, and last the small things that stand on surfaces,
on the furniture they belong on when the room has it (a TV on the TV stand, pillows at the
head of the bed). A few categories are arranged around another one (a nightstand beside the
bed, a coffee table in front of the sofa, a TV stand across from it). Each object tries a
handful of poses and is dropped if none is acceptable to the room's
:class:`~vlln.world.generator.room_space.RoomSpace`.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from itertools import chain

import numpy as np

from vlln.world.catalogue.base import Placement
from vlln.world.catalogue.registry import Catalogue
from vlln.world.generator import poses
from vlln.world.generator.attributes import describe, placement_words
from vlln.world.generator.contents import (
    ARRANGEMENTS,
    FLAT_HEIGHT,
    PlacementRequest,
    draw_requests,
    placement_phases,
)
from vlln.world.generator.doors import outer_sides
from vlln.world.generator.layout import FloorPlan
from vlln.world.generator.params import HouseParameters
from vlln.world.generator.poses import LocalBounds, Pose
from vlln.world.generator.rect import Rect
from vlln.world.generator.room_space import RoomSpace, footprint, rects_overlap
from vlln.world.mesh import Mesh
from vlln.world.model import Box3, ObjectInstance, Room

ARRANGED_GAP = {"beside": 0.05, "in front": 0.4}  # m from the anchor
LONG_OBJECT = 1.6  # m; free-standing objects this deep stand with their back to a wall (beds)
TABLE_HEIGHTS = (0.6, 1.0)  # m; a top in this range is a table for seats "at the table"
TABLE_WORDS = ("table", "desk", "island", "counter")  # category names that are worktops
SURFACE_HEIGHTS = (0.3, 1.6)  # m; small objects are put on surfaces in this height range
TALL_WALL_OBJECT = 1.5  # m; wall objects this tall (curtains) hang on outer walls only
WINDOW_COVERINGS = ("curtain", "blinds")  # hang on outer walls only, where windows would be
SEAT_ITEM_HEIGHT = 0.3  # m; seats and beds take only low things lying flat
SOFT_SUPPORTS = ("bed", "couch", "armchair", "bench", "beanbag", "ottoman", "crib")
# Small objects that belong on particular furniture go there when the room has it.
PREFERRED_SUPPORTS: dict[str, tuple[str, ...]] = {
    "pillow": ("bed", "couch", "armchair", "bench"),
    "cushion": ("couch", "armchair", "bench", "bed"),
    "blanket": ("bed", "couch", "armchair", "ottoman"),
    "sheet": ("bed", "drawer", "dresser", "shelf"),
    "tv": ("tv stand", "cabinet", "drawer", "dresser"),
    "computer monitor": ("desk",),
    "keyboard": ("desk",),
    "printer": ("desk", "cabinet", "shelf"),
    "microwave": ("counter", "kitchen island"),
    "coffee machine": ("counter", "kitchen island"),
    "kettle": ("counter", "kitchen island", "stove"),
    "toaster": ("counter", "kitchen island"),
    "table lamp": ("nightstand", "side table", "desk", "dresser", "drawer"),
    "mouse": ("desk",),
    "remote control": ("coffee table", "tv stand", "couch", "side table"),
    "pan": ("stove", "counter", "kitchen island"),
}
# Supports that hold only what prefers them: a stove's grate takes pans and kettles, not a
# bottle standing between its bars.
RESERVED_SUPPORTS = ("stove",)
FREE_STANDING = (Placement.FLOOR, Placement.AT_TABLE)  # may stand on rugs
FREE_STANDING_WORDS = tuple(p.value for p in FREE_STANDING)
POSE_TRIES = 16
SURFACE_GAP = 0.02  # m between objects on a surface and the surface edges


@dataclass
class _WorldSurface:
    owner: int
    owner_category: str
    height: float
    rect: Rect
    turns: int
    taken: list[Rect] = field(default_factory=list)


@dataclass
class FurnishedObject:
    """A placed instance and its mesh in world coordinates, carrying its instance id."""

    instance: ObjectInstance
    mesh: Mesh


def furnish(
    plan: FloorPlan, params: HouseParameters, catalogue: Catalogue, rng: np.random.Generator
) -> list[FurnishedObject]:
    """Objects for every room of the plan, with instance ids 1..N in placement order."""
    placed: list[FurnishedObject] = []
    rects = plan.rects
    for room, rect, outer in zip(plan.rooms, rects, outer_sides(rects), strict=True):
        space = RoomSpace.of_room(
            rect, room.ceiling_height, params.wall_thickness, plan.doors, room.id
        )
        requests = draw_requests(room, catalogue, params.clutter, rng, params.repeats)
        phases = placement_phases(requests)
        order = sorted(
            range(len(requests)), key=lambda i: (phases[i], -requests[i].footprint_area, i)
        )
        furnisher = _RoomFurnisher(room, rect, outer, space, rng, placed)
        furnisher.place_all([requests[i] for i in order])
    return placed


class _RoomFurnisher:
    """Places the requests of one room, appending what it placed to a shared list."""

    def __init__(
        self,
        room: Room,
        rect: Rect,
        outer_sides: set[str],
        space: RoomSpace,
        rng: np.random.Generator,
        placed: list[FurnishedObject],
    ) -> None:
        self.room = room
        self.rect = rect
        self.outer_sides = outer_sides
        self.space = space
        self.rng = rng
        self.placed = placed
        self.surfaces: list[_WorldSurface] = []
        self.tables: list[Rect] = []
        self.coverings: list[Rect] = []
        self.walled: list[Rect] = []  # footprints of things against walls: no rug under them
        self.anchors: list[tuple[str, str, Box3]] = []  # (category, wall side, box)

    def place_all(self, requests: list[PlacementRequest]) -> None:
        for request in requests:
            found = self._find(request)
            if found is not None:
                self._commit(request, *found)

    # ---- finding a pose -----------------------------------------------------------------

    def _find(self, req: PlacementRequest) -> tuple[Pose, str, _WorldSurface | None] | None:
        placement = req.category.placement
        if placement is Placement.ON_SURFACE:
            return self._on_surface(req)
        if placement is Placement.WALL_MOUNTED:
            return self._on_wall(req)
        if placement is Placement.CEILING:
            tries = poses.under_ceiling(
                self.space.interior, req.bounds, self.space.ceiling, self.rng, POSE_TRIES
            )
            pose = next(
                (p for p in tries if self.space.fits_above_floor(p.box(req.bounds), hangs=True)),
                None,
            )
            return None if pose is None else (pose, placement_words(placement), None)
        if req.bounds.height < FLAT_HEIGHT:
            return self._covering(req)
        interior = self.space.interior
        wall = _poses_only(poses.against_wall(interior, req.bounds, self.rng, POSE_TRIES))
        attempts: list[tuple[Placement, Iterable[Pose]]] = []
        if placement is Placement.FLOOR:
            if req.bounds.hi[2] - req.bounds.lo[2] >= LONG_OBJECT:
                centred = _poses_only(poses.centred_on_wall(interior, req.bounds, self.rng))
                attempts.append((placement, centred))
            attempts.append(
                (placement, poses.free_standing(interior, req.bounds, self.rng, POSE_TRIES))
            )
        elif placement is Placement.AT_TABLE:
            for table in self.tables:
                attempts.append((placement, poses.around_table(table, req.bounds, self.rng)))
            attempts.append((Placement.AGAINST_WALL, wall))
        elif placement is Placement.CORNER:
            corners = _poses_only(poses.in_corners(interior, req.bounds, self.rng))
            attempts += [(placement, corners), (Placement.AGAINST_WALL, wall)]
        else:
            attempts.append((placement, wall))
        if req.category.name in ARRANGEMENTS:
            attempts.insert(0, (placement, self._arranged(req)))
        for used, candidates in attempts:
            pose = self._first(req, candidates, on_rug=used in FREE_STANDING)
            if pose is not None:
                return pose, placement_words(used), None
        return None

    def _arranged(self, req: PlacementRequest) -> Iterator[Pose]:
        """Poses next to the anchors of an arranged category, nearest arrangement first."""
        anchor_name, how = ARRANGEMENTS[req.category.name]
        interior = self.space.interior
        for name, side, box in self.anchors:
            if name != anchor_name:
                continue
            if how == "beside":
                yield from poses.beside(interior, req.bounds, side, box, ARRANGED_GAP[how])
            elif how == "in front":
                yield poses.in_front_of(req.bounds, side, box, ARRANGED_GAP[how])
            else:
                yield from poses.across_from(interior, req.bounds, side, box)

    def _first(
        self, req: PlacementRequest, candidates: Iterable[Pose], on_rug: bool
    ) -> Pose | None:
        """The first pose that stands acceptably on the floor."""
        for pose in candidates:
            box = pose.box(req.bounds)
            rect = footprint(box)
            if not on_rug and any(rects_overlap(rect, rug) for rug in self.coverings):
                continue
            if self.space.fits_floor(box) and self.space.keeps_floor_walkable(rect):
                return pose
        return None

    def _covering(self, req: PlacementRequest) -> tuple[Pose, str, None] | None:
        """Rugs and mats: inside the room, not on another covering; furniture may stand on."""
        for pose in poses.free_standing(self.space.interior, req.bounds, self.rng, POSE_TRIES):
            rect = footprint(pose.box(req.bounds))
            if (
                self.space.contains(rect)
                and not any(rects_overlap(rect, other) for other in self.coverings)
                and not any(rects_overlap(rect, other) for other in self.walled)
            ):
                return pose, placement_words(req.category.placement), None
        return None

    def _on_wall(self, req: PlacementRequest) -> tuple[Pose, str, None] | None:
        # The model's origin (the bottom centre of its back) hangs at the category's height.
        y = req.category.wall_height
        tall = req.bounds.height > TALL_WALL_OBJECT or req.category.name in WINDOW_COVERINGS
        tries = 2 * POSE_TRIES  # walls have more free room than floors; keep looking
        interior = self.space.interior
        over = self._above_anchors(req, y)
        for side, pose in chain(over, poses.against_wall(interior, req.bounds, self.rng, tries, y)):
            if tall and side not in self.outer_sides:
                continue
            box = pose.box(req.bounds)
            axis, coord = poses.wall_line(self.rect, side)
            lo, hi = (box.min[0], box.max[0]) if axis == "x" else (box.min[2], box.max[2])
            if (
                box.min[1] >= 0.0
                and self.space.walls_clear_of_doors(axis, coord, lo, hi)
                and self.space.fits_above_floor(box, hangs=True)
            ):
                return pose, placement_words(Placement.WALL_MOUNTED), None
        return None

    def _above_anchors(self, req: PlacementRequest, y: float) -> Iterator[tuple[str, Pose]]:
        """Wall poses over the anchors of a category arranged "above" one (see ARRANGEMENTS)."""
        anchor_name, how = ARRANGEMENTS.get(req.category.name, ("", ""))
        if how != "above":
            return
        for name, side, box in self.anchors:
            if name == anchor_name:
                yield from poses.above(self.space.interior, req.bounds, side, box, y)

    def _on_surface(self, req: PlacementRequest) -> tuple[Pose, str, _WorldSurface] | None:
        preferred = PREFERRED_SUPPORTS.get(req.category.name, ())
        usable = [
            s
            for s in self.surfaces
            if SURFACE_HEIGHTS[0] <= s.height <= SURFACE_HEIGHTS[1]
            and s.rect.area > 0.0
            and (s.owner_category not in RESERVED_SUPPORTS or s.owner_category in preferred)
        ]
        if any(s.owner_category in preferred for s in usable):
            usable = [s for s in usable if s.owner_category in preferred]
        if not usable:
            return None
        areas = np.array([s.rect.area for s in usable])
        order = self.rng.choice(len(usable), size=len(usable), replace=False, p=areas / areas.sum())
        for k in order:
            surface = usable[int(k)]
            if not self._can_hold(surface, req.bounds):
                continue
            x0, x1, z0, z1 = req.bounds.turned(surface.turns)
            area = surface.rect.shrunk(SURFACE_GAP)
            if x1 - x0 > area.width or z1 - z0 > area.depth:
                continue
            y = surface.height - req.bounds.lo[1]
            back = surface.owner_category in SOFT_SUPPORTS  # pillows lie at the head or back
            for _ in range(3):
                ox = float(self.rng.uniform(area.x0 - x0, area.x1 - x1))
                oz = float(self.rng.uniform(area.z0 - z0, area.z1 - z1))
                if back:
                    ox, oz = _against_back(surface.turns, area, (x0, x1, z0, z1), ox, oz)
                pose = Pose(surface.turns, (ox, y, oz))
                box = pose.box(req.bounds)
                rect = footprint(box)
                if any(rects_overlap(rect, other, SURFACE_GAP) for other in surface.taken):
                    continue
                if self.space.fits_above_floor(box, ignore=surface.owner):
                    words = placement_words(Placement.ON_SURFACE, surface.owner_category)
                    return pose, words, surface
        return None

    def _can_hold(self, surface: _WorldSurface, bounds: LocalBounds) -> bool:
        """Whether the object fits under what is above the surface and suits a seat or bed."""
        above = [
            s.height
            for s in self.surfaces
            if s.owner == surface.owner
            and s.height > surface.height
            and rects_overlap(s.rect, surface.rect)
        ]
        headroom = min(above, default=self.space.ceiling) - surface.height - SURFACE_GAP
        if bounds.height > headroom:
            return False
        if surface.owner_category in SOFT_SUPPORTS:  # only low things lying flat
            lying = bounds.height <= min(bounds.hi[0] - bounds.lo[0], bounds.hi[2] - bounds.lo[2])
            return lying and bounds.height <= SEAT_ITEM_HEIGHT
        return True

    # ---- committing -----------------------------------------------------------------------

    def _commit(
        self, req: PlacementRequest, pose: Pose, placement: str, support: _WorldSurface | None
    ) -> None:
        instance_id = len(self.placed) + 1
        mesh = req.model.mesh.transformed(pose.yaw, pose.offset).with_instance_id(instance_id)
        lo, hi = mesh.bounds()
        box = Box3(
            (float(lo[0]), float(lo[1]), float(lo[2])), (float(hi[0]), float(hi[1]), float(hi[2]))
        )
        kind = req.category.placement
        if kind in (Placement.ON_SURFACE, Placement.WALL_MOUNTED, Placement.CEILING):
            self.space.add_object(instance_id, box)
        elif req.bounds.height < FLAT_HEIGHT:
            self.coverings.append(footprint(box))
        else:
            self.space.add_floor_object(instance_id, box)
            if placement not in FREE_STANDING_WORDS:
                self.walled.append(footprint(box))
            if placement == Placement.AGAINST_WALL.value:
                side = poses.SIDE_FACING[pose.turns]
                self.anchors.append((req.category.name, side, box))
        if support is not None:
            support.taken.append(footprint(box))
        if kind is not Placement.ON_SURFACE:
            self._add_surfaces(req, pose, instance_id)
        if kind in (Placement.FLOOR, Placement.AGAINST_WALL) and _is_table(req):
            self.tables.append(footprint(box))
        fine, attributes, caption = describe(req.category, req.style, placement, self.room.type)
        instance = ObjectInstance(
            id=instance_id,
            category=req.category.name,
            fine_category=fine,
            attributes=attributes,
            caption=caption,
            box=box,
            room_id=self.room.id,
            yaw=pose.yaw,
            support_id=None if support is None else support.owner,
        )
        self.placed.append(FurnishedObject(instance, mesh))

    def _add_surfaces(self, req: PlacementRequest, pose: Pose, instance_id: int) -> None:
        if req.category.placement is Placement.AT_TABLE:
            return  # nothing is put on the seats people sit on at a table
        for surface in req.model.surfaces:
            (cx, cz), (w, d) = surface.center, surface.size
            local = LocalBounds((cx - w / 2, 0.0, cz - d / 2), (cx + w / 2, 0.0, cz + d / 2))
            x0, x1, z0, z1 = local.turned(pose.turns)
            ox, oy, oz = pose.offset
            rect = Rect(x0 + ox, z0 + oz, x1 + ox, z1 + oz)
            self.surfaces.append(
                _WorldSurface(
                    instance_id,
                    req.category.name,
                    surface.height + oy,
                    rect,
                    pose.turns,
                )
            )


def _against_back(
    turns: int, area: Rect, extent: tuple[float, float, float, float], ox: float, oz: float
) -> tuple[float, float]:
    """The offset moved so the object touches the back edge of a surface facing ``turns``."""
    x0, x1, z0, z1 = extent
    return (
        (ox, area.z0 - z0),
        (area.x0 - x0, oz),
        (ox, area.z1 - z1),
        (area.x1 - x1, oz),
    )[turns % 4]


def _is_table(req: PlacementRequest) -> bool:
    name = req.category.name
    heights = [s.height for s in req.model.surfaces]
    return any(word in name for word in TABLE_WORDS) and any(
        TABLE_HEIGHTS[0] <= h <= TABLE_HEIGHTS[1] for h in heights
    )


def _poses_only(candidates: Iterable[tuple[str, Pose]]) -> Iterator[Pose]:
    return (pose for _, pose in candidates)
