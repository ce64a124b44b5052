"""A :class:`House` with geometry from a scan's triangles and its annotations.

Both scan formats come down to the same pieces: triangles with colours, annotated objects
(an oriented box, or the triangles they own), and regions. Triangles owned by no object are
structure, told apart by their normal and height: up-facing ones on a region's floor are
floor (what the navigable grid stands on), down-facing ones ceiling, the rest wall. What an
annotation is (object, shell, flight, void) comes from its mpcat40 group or raw word
(:mod:`vlln.world.scans.categories`); void annotations are dropped. Object categories are
mapped to the catalogue's names (:func:`map_category`); the mapping is part of the
:class:`ImportReport`. Flights of stairs are instances of category ``stairs`` when they can be
climbed, else shell too (:mod:`vlln.world.scans.flights`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from vlln.world.catalogue import default_catalogue
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.mesh import Mesh
from vlln.world.model import (
    Attributes,
    Box3,
    House,
    HouseGeometry,
    ObjectInstance,
    Point2,
    Room,
    StructureId,
)
from vlln.world.relations import build_relations
from vlln.world.scans.categories import (
    FLIGHT_WORDS,
    is_door_frame,
    is_flight,
    is_structure,
    is_void,
    word,
)
from vlln.world.scans.flights import FLIGHT_CATEGORY, flight_problem, taller_than_a_step

# Common scan names for catalogue categories (the scans' vocabularies are larger than ours).
SYNONYMS: dict[str, str] = {  # raw annotation words; the catalogue's aliases come on top
    "television": "tv",
    "tv monitor": "tv",
    "monitor": "computer monitor",
    "potted plant": "plant",
    "houseplant": "plant",
    "fridge": "refrigerator",
    "dining table": "table",
    "shelving": "shelf",
    "bookcase": "bookshelf",
    "lamp": "table lamp",
    "night stand": "nightstand",
    "trash": "garbage",
    "trash bin": "garbage",
    "garbage can": "garbage",
    "wastebasket": "garbage",
    "washer": "washing machine",
    "dryer": "clothes dryer",
    "coffee maker": "coffee machine",
    "bath tub": "bathtub",
    "tub": "bathtub",
}
STOREY_GAP = 1.0  # m: a room floor this far above its storey's lowest starts the next storey
_FLOOR_TOLERANCE = 0.15  # m: an up-facing triangle this close to a floor height is floor


@dataclass(frozen=True)
class ScanObject:
    """One annotated object: id, raw category, region, and an oriented box when the format has
    one (vlln frame; ``axes`` rows are unit vectors, ``half`` the half-extents along them);
    ``group`` is its mpcat40 group when the scan names one."""

    id: int
    category: str
    region: int
    center: tuple[float, float, float] | None = None
    axes: tuple[tuple[float, float, float], ...] | None = None
    half: tuple[float, float, float] | None = None
    group: str | None = None

    @property
    def void(self) -> bool:
        return is_void(self.category, self.group)

    @property
    def structure(self) -> bool:
        return is_structure(self.category, self.group)

    @property
    def flight(self) -> bool:
        return is_flight(self.category, self.group)


@dataclass
class ImportReport:
    """What an import found, for the user and the benchmarks."""

    scene: str
    triangles: int
    rooms: int
    instances: int
    structure_objects: int
    category_mapping: dict[str, str] = field(default_factory=dict)  # raw -> catalogue name
    unmapped: list[str] = field(default_factory=list)  # raw categories kept as they are
    flights_left_out: dict[int, str] = field(default_factory=dict)  # id -> why not climbable
    void_objects: int = 0  # annotations dropped as void (remove, unknown, no category...)
    seconds: float = 0.0


def map_category(raw: str) -> tuple[str, bool]:
    """The catalogue name for an annotation category, and whether the catalogue has it."""
    names = set(default_catalogue().names)
    phrase = word(raw)
    if phrase in FLIGHT_WORDS:
        return FLIGHT_CATEGORY, True
    for candidate in (phrase, SYNONYMS.get(phrase, ""), phrase.rstrip("s")):
        candidate = canonical_category(candidate)
        if candidate in names:
            return candidate, True
    return phrase, False


def on_storeys(rooms: list[Room]) -> list[Room]:
    """The rooms with the level and floor height of their storey. A scan's storeys are not
    exact (HM3D has none, and each region's floor lies a little above or below the next): a
    floor more than :data:`STOREY_GAP` above its storey's lowest starts the next storey, whose
    floor height is its rooms' median, so that the simulator finds one floor per storey."""
    storeys: list[list[float]] = []
    for y in sorted(room.floor_y for room in rooms):
        if not storeys or y - storeys[-1][0] > STOREY_GAP:
            storeys.append([])
        storeys[-1].append(y)
    storey_of = {
        y: (float(np.median(heights)), level)
        for level, heights in enumerate(storeys)
        for y in heights
    }
    return [
        replace(room, floor_y=storey_of[room.floor_y][0], level=storey_of[room.floor_y][1])
        for room in rooms
    ]


def owners_by_box(triangles: NDArray[np.float64], objects: list[ScanObject]) -> NDArray[np.int64]:
    """Per triangle, the id of the smallest object box holding all three corners (-1: none);
    a large floor or wall triangle reaching out of a box is never the object's."""
    owner = np.full(len(triangles), -1, np.int64)
    best = np.full(len(triangles), np.inf)
    lo, hi = triangles.min(axis=1), triangles.max(axis=1)
    by_x = np.argsort(lo[:, 0], kind="stable")  # a box only looks at triangles starting in it
    sorted_x = lo[by_x, 0]
    for obj in objects:
        if obj.center is None or obj.axes is None or obj.half is None:
            continue
        half = np.asarray(obj.half) + 1e-3
        reach = np.abs(np.asarray(obj.axes)).T @ half
        low, high = np.asarray(obj.center) - reach, np.asarray(obj.center) + reach
        first = np.searchsorted(sorted_x, low[0], side="left")
        last = np.searchsorted(sorted_x, high[0], side="right")
        span = by_x[first:last]
        span = span[np.all((lo[span] >= low) & (hi[span] <= high), axis=1)]
        local = (triangles[span] - np.asarray(obj.center)) @ np.asarray(obj.axes).T
        hit = span[np.all(np.abs(local) <= half, axis=(1, 2))]
        volume = float(np.prod(2 * half))
        take = hit[volume < best[hit]]
        owner[take] = obj.id
        best[take] = volume
    return owner


def build_house(
    name: str,
    triangles: NDArray[np.float64],
    colours: NDArray[np.float64],
    objects: list[ScanObject],
    rooms: list[Room],
    owners: NDArray[np.int64] | None = None,
) -> tuple[House, ImportReport]:
    """The house: the rooms on their storeys (:func:`on_storeys`), one instance per object
    that is neither structure nor void, one mesh."""
    void = [o.id for o in objects if o.void]
    objects = [o for o in objects if not o.void]
    frames = [o for o in objects if is_door_frame(o.category)]
    if owners is None:
        owners = owners_by_box(triangles, [o for o in objects if not o.structure])
        in_frame = owners_by_box(triangles, frames) >= 0
    else:
        owners = np.where(np.isin(owners, void), -1, owners)
        in_frame = np.isin(owners, [o.id for o in frames])
    ids = _structure_ids(triangles, rooms)  # each region's own floor height tells floor
    rooms = on_storeys(rooms)
    flights = [o.id for o in objects if o.flight]
    if flights:
        owners = np.where(np.isin(owners, flights) & taller_than_a_step(triangles), -1, owners)
    floor_ys = sorted({room.floor_y for room in rooms})
    left_out: dict[int, str] = {}
    for flight in flights:
        problem = flight_problem(triangles[owners == flight], floor_ys)
        if problem is not None:
            left_out[flight] = problem
    structure = {o.id for o in objects if o.structure} | set(left_out)
    owners = np.where(np.isin(owners, list(structure)), -1, owners)
    ids[in_frame] = int(StructureId.DOOR_FRAME)
    ids = np.where(owners >= 0, owners, ids)

    report = ImportReport(name, len(triangles), len(rooms), 0, len(structure))
    report.flights_left_out = left_out
    report.void_objects = len(void)
    region_room = {room.id: room.id for room in rooms}
    instances: list[ObjectInstance] = []
    for obj in objects:
        if obj.id in structure:
            continue
        mine = triangles[owners == obj.id].reshape(-1, 3)
        box = _box_of(obj, mine)
        if box is None:
            continue  # an object with neither a box nor triangles cannot be placed
        category, known = (FLIGHT_CATEGORY, True) if obj.flight else map_category(obj.category)
        if category == FLIGHT_CATEGORY and not obj.flight:
            category = word(obj.category)  # a stair word whose group is not stairs (a rail)
        report.category_mapping[obj.category] = category
        if not known and obj.category not in report.unmapped:
            report.unmapped.append(obj.category)
        instances.append(
            ObjectInstance(
                id=obj.id,
                category=category,
                fine_category=obj.category,
                attributes=Attributes(),
                caption="",
                box=box,
                room_id=region_room.get(obj.region, _room_containing(rooms, box)),
            )
        )
    instances.sort(key=lambda inst: inst.id)
    report.instances = len(instances)
    report.unmapped.sort()
    order = _draw_order(triangles, ids)
    mesh = _mesh(triangles[order], colours[order], ids[order])
    house = House(
        name=name,
        rooms=rooms,
        doors=[],
        instances=instances,
        relations=build_relations(instances),
        geometry=HouseGeometry(mesh),
    )
    return house, report


def _box_of(obj: ScanObject, points: NDArray[np.float64]) -> Box3 | None:
    if obj.center is not None and obj.axes is not None and obj.half is not None:
        extent = np.abs(np.asarray(obj.axes)).T @ np.asarray(obj.half)
        lo = np.asarray(obj.center) - extent
        hi = np.asarray(obj.center) + extent
    elif len(points):
        lo, hi = points.min(axis=0), points.max(axis=0)
    else:
        return None
    return Box3(
        (float(lo[0]), float(lo[1]), float(lo[2])), (float(hi[0]), float(hi[1]), float(hi[2]))
    )


def _room_containing(rooms: list[Room], box: Box3) -> int:
    from vlln.world.scene_summary import UNKNOWN_ROOM_ID

    x, _, z = box.center
    below = [room for room in rooms if room.floor_y <= box.min[1] + 0.05] or rooms
    for room in sorted(below, key=lambda room: -room.floor_y):  # the storey it stands on
        if _inside((x, z), room.polygon):
            return room.id
    return UNKNOWN_ROOM_ID


def _inside(point: Point2, polygon: tuple[Point2, ...]) -> bool:
    p = np.asarray(polygon) - np.asarray(point)
    q = np.roll(p, -1, axis=0)
    crosses = (p[:, 1] > 0) != (q[:, 1] > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        x_at = p[:, 0] - p[:, 1] * (q[:, 0] - p[:, 0]) / (q[:, 1] - p[:, 1])
    return bool(np.count_nonzero(crosses & (x_at > 0)) % 2)


def _structure_ids(triangles: NDArray[np.float64], rooms: list[Room]) -> NDArray[np.int64]:
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    up = normals[:, 1] / np.maximum(lengths, 1e-12)
    heights = triangles[:, :, 1]
    floors = sorted({room.floor_y for room in rooms}) or [float(heights.min())]
    near_floor = np.zeros(len(triangles), bool)
    for y in floors:
        near_floor |= np.all(np.abs(heights - y) <= _FLOOR_TOLERANCE, axis=1)
    ids = np.full(len(triangles), int(StructureId.WALL), np.int64)
    ids[up < -0.7] = int(StructureId.CEILING)
    ids[(up > 0.7) & near_floor] = int(StructureId.FLOOR)
    return ids


_CELL = 1.0  # m: triangles of one id are ordered by the 1 m cell their centre is in


def _draw_order(triangles: NDArray[np.float64], ids: NDArray[np.int64]) -> NDArray[np.intp]:
    """Triangles grouped by id, then by cell along a Z-order curve, so that every run of a
    long id (a scan's walls) is spatially compact and the renderer can cull its pieces."""
    cells = np.floor(triangles.mean(axis=1) / _CELL).astype(np.int64)
    cells -= cells.min(axis=0)
    key = np.zeros(len(triangles), np.int64)
    for bit in range(10):  # interleave the bits of the three cell coordinates
        for axis in range(3):
            key |= ((cells[:, axis] >> bit) & 1) << (3 * bit + axis)
    order: NDArray[np.intp] = np.lexsort((key, ids))
    return order


def _mesh(
    triangles: NDArray[np.float64], colours: NDArray[np.float64], ids: NDArray[np.int64]
) -> Mesh:
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    n = len(triangles) * 3
    return Mesh(
        positions=triangles.reshape(-1, 3).astype(np.float32),
        normals=np.repeat(normals, 3, axis=0).astype(np.float32),
        uvs=triangles.reshape(-1, 3)[:, [0, 2]].astype(np.float32),
        colors=colours.reshape(-1, 3).astype(np.float32),
        materials=np.zeros(n, np.int32),
        instance_ids=np.repeat(ids, 3).astype(np.int32),
    )
