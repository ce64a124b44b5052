"""Matterport3D scenes: ``<scene>/<scene>.glb`` plus the ``<scene>.house`` annotations.

The ``.house`` file is ASCII, one record per line, a letter first (Matterport3D's
``house_segmentations`` format, version ``ASCII 1.1``); the records read here are::

    H name label #images #panoramas #vertices #surfaces #segments #objects #categories
      #regions #portals #levels  0 0 0 0 0  xlo ylo zlo xhi yhi zhi  0 0 0 0 0
    L level_index #regions label  px py pz  xlo ylo zlo xhi yhi zhi  0 0 0 0 0
    R region_index level_index 0 0 label  px py pz  xlo ylo zlo xhi yhi zhi  height  0 0 0 0
    S surface_index region_index 0 label  px py pz  nx ny nz  xlo ylo zlo xhi yhi zhi  0 0 0 0 0
    V vertex_index surface_index label  px py pz  nx ny nz  0 0 0
    C category_index mapping_index mapping_name mpcat40_index mpcat40_name  0 0 0 0 0
    O object_index region_index category_index  px py pz  a0x a0y a0z  a1x a1y a1z
      r0 r1 r2  0 0 0 0 0 0 0 0

(I, P and E records are read past.) A region's floor polygon is its surface's vertices; a
region label is one letter (``b`` bedroom, ``k`` kitchen, ...; :data:`REGION_LETTERS`); an
object is an oriented box (centre, two axes, radii), its category the ``C`` record at that
index (``-1``: none): the raw word (``#`` for spaces) and its mpcat40 group, which decide
what the annotation is (:mod:`vlln.world.scans.categories`). Coordinates are z-up (see
:mod:`vlln.world.scans.gltf`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from vlln.errors import DataFormatError
from vlln.files import write_text_atomic
from vlln.world.mesh import Mesh
from vlln.world.model import Door, House, Room, StructureId
from vlln.world.scans.build import ImportReport, ScanObject, build_house
from vlln.world.scans.categories import NO_CATEGORY, mpcat40_group, mpcat40_of
from vlln.world.scans.checks import house_text
from vlln.world.scans.gltf import from_scan_frame, read_glb, to_scan_frame, write_glb

# Our room type -> Matterport3D region letter; the other letters are read as the nearest type.
REGION_LETTERS: dict[str, str] = {
    "bathroom": "a",
    "bedroom": "b",
    "storage room": "c",
    "dining room": "d",
    "open area": "e",
    "corridor": "h",
    "kitchen": "k",
    "living room": "l",
    "study": "o",
    "stairs": "s",
    "toilet": "t",
    "gym": "w",
    "other": "z",
}
_MORE_LETTERS = {
    "f": "living room", "g": "storage room", "i": "study", "j": "storage room", "m": "study",
    "n": "living room", "p": "open area", "r": "living room", "u": "storage room",
    "v": "living room", "x": "open area", "y": "open area", "B": "living room",
    "C": "study", "D": "dining room", "S": "bathroom", "Z": "other", "-": "other",
}  # fmt: skip
LETTER_TO_TYPE = {**_MORE_LETTERS, **{letter: kind for kind, letter in REGION_LETTERS.items()}}


def import_mp3d(scene_dir: Path) -> tuple[House, ImportReport]:
    name = scene_dir.name
    triangles, colours = read_glb(scene_dir / f"{name}.glb")
    rooms, objects = read_house_file(scene_dir / f"{name}.house")
    return build_house(name, triangles, colours, objects, rooms)


def read_house_file(path: Path) -> tuple[list[Room], list[ScanObject]]:
    """Rooms (regions with their floor polygons) and objects of a ``.house`` file."""
    if not path.is_file():
        raise DataFormatError(f"{path} does not exist; a Matterport3D scene needs its .house file")
    regions: dict[int, tuple[int, str, float, float]] = {}
    surfaces: dict[int, int] = {}  # surface -> region
    polygons: dict[int, list[tuple[float, float]]] = {}
    categories: dict[int, tuple[str, str | None]] = {}  # index -> raw word, mpcat40 group
    raw_objects: list[tuple[tuple[int, int, int], list[float]]] = []  # ids, numbers
    for number, line in enumerate(house_text(path).splitlines(), 1):
        fields = line.split()
        if not fields:
            continue
        try:
            kind = fields[0]
            if kind == "R":
                zlo, zhi = _number(fields[11]), _number(fields[14])
                regions[_index(fields[1])] = (_index(fields[2]), fields[5], zlo, zhi)
            elif kind == "S":
                surfaces[_index(fields[1])] = _index(fields[2])
            elif kind == "V":
                x, y = _number(fields[4]), _number(fields[5])
                polygons.setdefault(_index(fields[2]), []).append((x, -y))
            elif kind == "C":
                group = mpcat40_group(_index(fields[4]), fields[5]) if len(fields) > 5 else None
                categories[_index(fields[1])] = (fields[3].replace("#", " "), group)
            elif kind == "O":
                numbers = [_number(v) for v in fields[4:16]]
                ids = (_index(fields[1]), _index(fields[2]), _index(fields[3]))
                raw_objects.append((ids, numbers))
        except (IndexError, ValueError):
            raise DataFormatError(
                f"{path}:{number}: a {fields[0]!r} record with too few fields, or one that is "
                "not a finite number; copy the scan's .house file again"
            ) from None
    rooms = []
    for region_id, (_level, label, zlo, zhi) in sorted(regions.items()):
        polygon = next(
            (tuple(polygons.get(s, [])) for s, r in surfaces.items() if r == region_id), ()
        )
        if len(polygon) < 3:
            raise DataFormatError(
                f"{path}: region {region_id} has no floor polygon (S and V records)"
            )
        rooms.append(
            Room(
                id=region_id,
                type=LETTER_TO_TYPE.get(label, "other"),
                polygon=polygon,
                floor_y=zlo,
                ceiling_height=zhi - zlo,
            )
        )
    objects = []
    for (object_id, region, category), numbers in raw_objects:
        centre, a0, a1 = from_scan_frame(np.array(numbers[:9]).reshape(3, 3))
        a2 = np.cross(a0, a1)
        raw, group = categories.get(category, (NO_CATEGORY, None))
        objects.append(
            ScanObject(
                id=object_id,
                category=raw,
                region=region,
                center=(float(centre[0]), float(centre[1]), float(centre[2])),
                axes=tuple((float(a[0]), float(a[1]), float(a[2])) for a in (a0, a1, a2)),
                half=(numbers[9], numbers[10], numbers[11]),
                group=group,
            )
        )
    return rooms, objects


def _number(text: str) -> float:
    """A coordinate or size: NaN or infinity (``nan``, ``inf``, or digits past the float
    range) would pass ``float`` and poison every distance computed from it."""
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(text)
    return value


def _index(text: str) -> int:
    """An index or count; real ones have a few digits, and ``int`` refuses 4,300 or more."""
    if len(text) > 18:
        raise ValueError(text)
    return int(text)


def export_mp3d(house: House, out_dir: Path) -> Path:
    """``<out_dir>/<name>/<name>.glb`` and ``<name>.house``; returns the scene folder."""
    if house.geometry is None:
        raise DataFormatError(f"house {house.name!r} has no geometry to export")
    scene_dir = out_dir / house.name
    mesh = house.geometry.mesh
    write_glb(scene_dir / f"{house.name}.glb", mesh.positions.reshape(-1, 3, 3), mesh.colors)
    write_text_atomic(scene_dir / f"{house.name}.house", _house_text(house))
    return scene_dir


def _fmt(values: list[float] | tuple[float, ...] | np.ndarray) -> str:
    return " ".join(f"{float(v):.6f}" for v in values)


def _house_text(house: House) -> str:
    categories = sorted({inst.category for inst in house.instances} | {"door frame"})
    lo, hi = house.geometry.mesh.bounds() if house.geometry else (np.zeros(3), np.zeros(3))
    box = to_scan_frame(np.array([lo, hi]))
    scan_lo, scan_hi = box.min(axis=0), box.max(axis=0)
    floors = sorted({room.floor_y for room in house.rooms})
    lines = [
        "ASCII 1.1",
        f"H {house.name} house 0 0 {sum(len(r.polygon) for r in house.rooms)} "
        f"{len(house.rooms)} 0 {len(house.instances)} {len(categories)} {len(house.rooms)} 0 "
        f"{len(floors)} 0 0 0 0 0 {_fmt(scan_lo)} {_fmt(scan_hi)} 0 0 0 0 0",
    ]
    for level, y in enumerate(floors):
        count = sum(1 for room in house.rooms if room.floor_y == y)
        lines.append(
            f"L {level} {count} level 0 0 {y:.6f} {_fmt(scan_lo)} {_fmt(scan_hi)} 0 0 0 0 0"
        )
    vertex = 0
    for room in house.rooms:
        xs = [x for x, _ in room.polygon]
        zs = [z for _, z in room.polygon]
        top = room.floor_y + room.ceiling_height
        rlo = (min(xs), -max(zs), room.floor_y)
        rhi = (max(xs), -min(zs), top)
        centre = ((rlo[0] + rhi[0]) / 2, (rlo[1] + rhi[1]) / 2, room.floor_y)
        letter = REGION_LETTERS.get(room.type, "z")
        level = floors.index(room.floor_y)
        lines.append(
            f"R {room.id} {level} 0 0 {letter} {_fmt(centre)} {_fmt(rlo)} {_fmt(rhi)} "
            f"{room.ceiling_height:.6f} 0 0 0 0"
        )
        bounds = f"{_fmt(rlo)} {_fmt(rhi)}"
        lines.append(f"S {room.id} {room.id} 0 {letter} {_fmt(centre)} 0 0 1 {bounds} 0 0 0 0 0")
        for x, z in room.polygon:
            lines.append(f"V {vertex} {room.id} {letter} {_fmt((x, -z, room.floor_y))} 0 0 1 0 0 0")
            vertex += 1
    for index, category in enumerate(categories):
        word = category.replace(" ", "#")
        group, group_name = mpcat40_of(category)
        lines.append(f"C {index} {index + 1} {word} {group} {group_name} 0 0 0 0 0")
    for inst in sorted(house.instances, key=lambda i: i.id):
        centre = to_scan_frame(np.array([inst.box.center]))[0]
        sx, sy, sz = inst.box.size
        # Scan axes: x, then the scan's y (our -z); radii follow them (our z extent, then y).
        lines.append(
            f"O {inst.id} {inst.room_id} {categories.index(inst.category)} {_fmt(centre)} "
            f"1 0 0 0 1 0 {_fmt((sx / 2, sz / 2, sy / 2))} 0 0 0 0 0 0 0 0"
        )
    following = max((inst.id for inst in house.instances), default=0)
    frame = categories.index("door frame")
    boxes = _door_frame_boxes(house.doors, house.geometry.mesh) if house.geometry else []
    for door, (low, high) in zip(house.doors, boxes, strict=False):
        if low is None or high is None:
            continue
        following += 1
        centre = to_scan_frame(np.array([(low + high) / 2]))[0]
        sx, sy, sz = high - low
        lines.append(
            f"O {following} {door.room_a} {frame} {_fmt(centre)} "
            f"1 0 0 0 1 0 {_fmt((sx / 2, sz / 2, sy / 2))} 0 0 0 0 0 0 0 0"
        )
    return "\n".join(lines) + "\n"


def _door_frame_boxes(
    doors: list[Door], mesh: Mesh
) -> list[tuple[np.ndarray | None, np.ndarray | None]]:
    """Per door, the box of the door-frame triangles around it (``None`` when it has none)."""
    triangles = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
    framed = triangles[mesh.instance_ids[::3] == int(StructureId.DOOR_FRAME)]
    centres = framed.mean(axis=1)[:, [0, 2]]
    boxes: list[tuple[np.ndarray | None, np.ndarray | None]] = []
    for door in doors:
        near = np.linalg.norm(centres - np.asarray(door.center), axis=1) <= door.width / 2 + 0.3
        if not near.any():
            boxes.append((None, None))
            continue
        points = framed[near].reshape(-1, 3)
        boxes.append((points.min(axis=0), points.max(axis=0)))
    return boxes
