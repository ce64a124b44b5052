"""HM3D scenes: ``<scene>.glb`` (what is drawn), ``<scene>.semantic.glb`` (the same surfaces,
each object painted in its own colour) and ``<scene>.semantic.txt``.

``semantic.txt`` starts with a title line, then one object per line:
``id,hexcolor,"category",region`` (``1,9E8A3B,"chair",3``). A drawn triangle belongs to the
object whose colour the nearest semantic triangle has. HM3D regions have no labels or
outlines: a room is a region, its outline the convex hull of its ``floor`` object, its storey
found from its floor's height, its type ``other`` unless the scene's summary
(``region_dict.json``) names it.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
from matplotlib.path import Path as MplPath
from numpy.typing import NDArray
from scipy.spatial import ConvexHull, cKDTree

from vlln.errors import DataFormatError
from vlln.files import write_text_atomic
from vlln.world.model import House, Room, StructureId
from vlln.world.scans.build import ImportReport, ScanObject, build_house
from vlln.world.scans.checks import semantic_text
from vlln.world.scans.gltf import read_glb, write_glb

TITLE = "HM3D Semantic Annotations"
_STRUCTURE_NAMES = {
    int(StructureId.WALL): "wall",
    int(StructureId.CEILING): "ceiling",
    int(StructureId.DOOR_FRAME): "door frame",
}
_FLOOR_BAND = 0.15  # m: a room's floor triangles lie this close to its floor height


def import_hm3d(scene_dir: Path) -> tuple[House, ImportReport]:
    name = scene_dir.name
    triangles, colours = read_glb(scene_dir / f"{name}.glb")
    semantic, paint = read_glb(scene_dir / f"{name}.semantic.glb")
    objects, by_colour = read_semantic_txt(scene_dir / f"{name}.semantic.txt")
    codes = _colour_codes(paint[:, 0])
    semantic_owner = np.array([by_colour.get(int(c), -1) for c in codes], np.int64)
    if len(semantic) == len(triangles) and np.allclose(semantic, triangles, atol=1e-4):
        owners = semantic_owner
    else:
        _, nearest = cKDTree(semantic.mean(axis=1)).query(triangles.mean(axis=1))
        owners = semantic_owner[nearest]
    rooms = _rooms(triangles, owners, objects)
    return build_house(name, triangles, colours, objects, rooms, owners)


def read_semantic_txt(path: Path) -> tuple[list[ScanObject], dict[int, int]]:
    """The objects and a map from colour (24-bit int) to object id."""
    if not path.is_file():
        raise DataFormatError(f"{path} does not exist; an HM3D scene needs its semantic.txt")
    objects: list[ScanObject] = []
    by_colour: dict[int, int] = {}
    lines = semantic_text(path).splitlines()
    for number, row in enumerate(csv.reader(lines[1:]), 2):
        if not row:
            continue
        try:
            object_id, colour, category, region = int(row[0]), int(row[1], 16), row[2], int(row[3])
        except (IndexError, ValueError):
            raise DataFormatError(
                f'{path}:{number}: expected id,hexcolor,"category",region, got {",".join(row)!r}'
            ) from None
        objects.append(ScanObject(object_id, category, region))
        by_colour[colour] = object_id
    return objects, by_colour


def _colour_codes(rgb: NDArray[np.float64]) -> NDArray[np.int64]:
    bytes_ = np.round(np.clip(rgb, 0.0, 1.0) * 255).astype(np.int64)
    codes: NDArray[np.int64] = (bytes_[:, 0] << 16) | (bytes_[:, 1] << 8) | bytes_[:, 2]
    return codes


def _rooms(
    triangles: NDArray[np.float64], owners: NDArray[np.int64], objects: list[ScanObject]
) -> list[Room]:
    rooms = []
    for obj in objects:
        if obj.category != "floor" or obj.region < 0:
            continue
        points = triangles[owners == obj.id].reshape(-1, 3)
        if len(points) < 3:
            continue
        plan = points[:, [0, 2]]
        hull = plan[ConvexHull(plan).vertices]
        polygon = tuple((float(x), float(z)) for x, z in hull)
        rooms.append(
            Room(id=obj.region, type="other", polygon=polygon, floor_y=float(points[:, 1].min()))
        )
    return sorted(rooms, key=lambda r: r.id)


def export_hm3d(house: House, out_dir: Path) -> Path:
    """The three HM3D files in ``<out_dir>/<name>/``; returns that folder."""
    if house.geometry is None:
        raise DataFormatError(f"house {house.name!r} has no geometry to export")
    mesh = house.geometry.mesh
    triangles = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
    ids = mesh.instance_ids[::3].astype(np.int64)
    owner = ids.copy()
    rows: list[tuple[int, str, int]] = [(i.id, i.category, i.room_id) for i in house.instances]
    following = max((i.id for i in house.instances), default=0)
    centres = triangles.mean(axis=1)[:, [0, 2]]
    heights = triangles[:, :, 1].mean(axis=1)
    for room in house.rooms:  # one floor object per room, on the room's own storey
        following += 1
        inside = MplPath(np.asarray(room.polygon)).contains_points(centres)
        level = np.abs(heights - room.floor_y) <= _FLOOR_BAND
        mine = (ids == int(StructureId.FLOOR)) & inside & level
        owner[mine] = following
        rows.append((following, "floor", room.id))
    for structure, word in _STRUCTURE_NAMES.items():
        following += 1
        owner[ids == structure] = following
        rows.append((following, word, -1))
    colour_of = {object_id: 97 * (k + 1) for k, (object_id, _, _) in enumerate(rows)}
    codes = np.array([colour_of.get(int(o), 0) for o in owner], np.int64)
    paint = np.stack([(codes >> 16) & 255, (codes >> 8) & 255, codes & 255], axis=1) / 255.0
    scene_dir = out_dir / house.name
    write_glb(scene_dir / f"{house.name}.glb", triangles, mesh.colors)
    write_glb(scene_dir / f"{house.name}.semantic.glb", triangles, np.repeat(paint, 3, axis=0))
    lines = [TITLE] + [
        f'{object_id},{colour_of[object_id]:06X},"{category}",{region}'
        for object_id, category, region in rows
    ]
    write_text_atomic(scene_dir / f"{house.name}.semantic.txt", "\n".join(lines) + "\n")
    return scene_dir
