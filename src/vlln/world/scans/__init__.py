"""Scanned scenes: Matterport3D and HM3D import, and export of any house in their layouts.

A scene folder ``<dir>/<scene>/`` holds ``<scene>.glb`` and either ``<scene>.house``
(Matterport3D) or ``<scene>.semantic.glb`` + ``<scene>.semantic.txt`` (HM3D). When the folder
also holds the reference's scene summary (``object_dict.json``, ``region_dict.json``), its
words win: categories, attributes, captions, boxes and relations of the instances it lists,
and the rooms (HM3D has no room labels of its own).
"""

from __future__ import annotations

import logging
import time
from dataclasses import replace
from pathlib import Path

from vlln.errors import ConfigError, DataFormatError
from vlln.world.model import House, HouseGeometry
from vlln.world.scans.build import ImportReport, map_category
from vlln.world.scans.hm3d import export_hm3d, import_hm3d
from vlln.world.scans.mp3d import export_mp3d, import_mp3d
from vlln.world.scene_summary import OBJECT_DICT_FILE, export_scene_summary, import_scene_summary

STYLES = ("mp3d", "hm3d")
logger = logging.getLogger(__name__)

__all__ = [
    "STYLES",
    "ImportReport",
    "export_scene",
    "import_scene",
    "load_scene",
    "map_category",
    "with_subdivided_mesh",
]


def scene_style(scene_dir: Path) -> str:
    """``"mp3d"`` or ``"hm3d"``, from the files the folder holds."""
    name = scene_dir.name
    if (scene_dir / f"{name}.house").is_file():
        return "mp3d"
    if (scene_dir / f"{name}.semantic.txt").is_file():
        return "hm3d"
    raise DataFormatError(
        f"{scene_dir} is not a scene folder: expected {name}.glb with {name}.house "
        f"(Matterport3D) or with {name}.semantic.glb and {name}.semantic.txt (HM3D)"
    )


def import_scene(scene_dir: str | Path) -> tuple[House, ImportReport]:
    """The house of a scene folder with its geometry, and what the import found."""
    scene_dir = Path(scene_dir)
    started = time.perf_counter()
    importer = import_mp3d if scene_style(scene_dir) == "mp3d" else import_hm3d
    house, report = importer(scene_dir)
    if not house.rooms:
        raise DataFormatError(
            f"{scene_dir} yields no rooms (Matterport3D: regions with floor polygons; HM3D: "
            "'floor' objects with a region), so nothing could be navigated; give a complete scan"
        )
    for flight, problem in report.flights_left_out.items():
        logger.warning(
            "%s: the stairs %d cannot be climbed (%s); they are kept as walls, so the storeys "
            "they would join stay apart",
            scene_dir.name,
            flight,
            problem,
        )
    if (scene_dir / OBJECT_DICT_FILE).is_file():
        house = _with_summary(house, import_scene_summary(scene_dir))
    report.seconds = time.perf_counter() - started
    return house, report


def load_scene(scene_dir: str | Path) -> House:
    return import_scene(scene_dir)[0]


def export_scene(house: House, out_dir: str | Path, style: str) -> Path:
    """Write ``house`` as a ``style`` scene folder with its scene summary; returns the folder."""
    if style not in STYLES:
        raise ConfigError(f"unknown scene style {style!r}; choose one of: {', '.join(STYLES)}")
    exporter = export_mp3d if style == "mp3d" else export_hm3d
    scene_dir = exporter(house, Path(out_dir))
    export_scene_summary(house, Path(out_dir))
    return scene_dir


def with_subdivided_mesh(house: House, times: int) -> House:
    """``house`` with every triangle split into ``4**times`` (:meth:`Mesh.subdivided`): the
    same rooms, objects and look at a real scan's triangle count, to measure import and
    rendering speed on (``vlln world export --subdivide 2``)."""
    if not 0 <= times <= 4:
        raise ConfigError(f"--subdivide {times} is out of range; use 0 to 4 (each step: 4x)")
    if house.geometry is None:
        raise DataFormatError(f"house {house.name!r} has no geometry to subdivide")
    return replace(house, geometry=HouseGeometry(house.geometry.mesh.subdivided(times)))


def _with_summary(house: House, summary: House) -> House:
    words = {inst.id: inst for inst in summary.instances}
    rooms = house.rooms
    room_ids = {room.id for room in house.rooms}
    if all(room.type == "other" for room in house.rooms) and summary.rooms:
        floors = {room.id: room for room in house.rooms}
        rooms = [
            replace(room, floor_y=floors[room.id].floor_y, level=floors[room.id].level)
            if room.id in floors
            else room
            for room in summary.rooms
        ]
        room_ids = {room.id for room in rooms}
    instances = []
    for inst in house.instances:
        said = words.get(inst.id)
        if said is None:
            instances.append(inst)
            continue
        instances.append(
            replace(
                inst,
                category=said.category,
                fine_category=said.fine_category or inst.fine_category,
                attributes=said.attributes,
                caption=said.caption,
                box=said.box,
                room_id=said.room_id if said.room_id in room_ids else inst.room_id,
            )
        )
    return replace(
        house,
        rooms=rooms,
        instances=instances,
        relations=summary.relations or house.relations,
        instance_keys=summary.instance_keys,
    )
