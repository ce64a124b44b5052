"""Writing a house as a scene summary, byte-identical for equal houses."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

from vlln.errors import DataFormatError
from vlln.files import write_text_atomic
from vlln.world.model import House, Point2, Room
from vlln.world.scene_summary.format import (
    DECIMALS,
    DESCRIPTION_KEYS,
    ENLARGE_MARGIN,
    FINE_CATEGORY_KEY,
    OBJECT_DICT_FILE,
    REGION_DICT_FILE,
    ROOM_TYPE_TO_LABEL,
    UNKNOWN_ROOM_ID,
    grown_polygon,
)


def export_scene_summary(house: House, out_dir: str | Path) -> Path:
    """Write ``house`` to ``<out_dir>/<house.name>/`` and return that directory."""
    name = house.name
    if not name or name in (".", "..") or "/" in name or "\\" in name:
        raise DataFormatError(
            f"house name {name!r} cannot be a scene directory name; use a non-empty name "
            "without path separators"
        )
    scene_dir = Path(out_dir) / name
    write_text_atomic(scene_dir / OBJECT_DICT_FILE, _to_json(_object_dict(house)))
    write_text_atomic(scene_dir / REGION_DICT_FILE, _to_json(_region_dict(house)))
    return scene_dir


def _num(value: float) -> float:
    if not math.isfinite(value):
        raise DataFormatError(f"cannot write the non-finite number {value!r} to a scene summary")
    return round(float(value), DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0


def _plan_points(polygon: tuple[Point2, ...] | list[Point2]) -> list[list[float]]:
    return [[_num(x), _num(-z)] for x, z in polygon]


def _room_label(room: Room) -> str:
    if room.type not in ROOM_TYPE_TO_LABEL:
        raise DataFormatError(
            f"room {room.id} has type {room.type!r}, which the scene-summary format cannot "
            f"express; valid types: {sorted(ROOM_TYPE_TO_LABEL)}"
        )
    return ROOM_TYPE_TO_LABEL[room.type]


def _object_dict(house: House) -> dict[str, Any]:
    labels = {room.id: _room_label(room) for room in house.rooms}
    scopes = {room.id: _scope(house, room.level) for room in house.rooms}
    nearby: dict[int, dict[str, list[str]]] = {}
    for rel in sorted(house.relations, key=lambda r: (r.subject, r.object)):
        nearby.setdefault(rel.subject, {}).setdefault(str(rel.object), []).append(rel.word)
    out: dict[str, Any] = {}
    for inst in sorted(house.instances, key=lambda i: i.id):
        if inst.room_id != UNKNOWN_ROOM_ID and inst.room_id not in labels:
            raise DataFormatError(
                f"instance {inst.id} of house {house.name!r} is in room {inst.room_id}, which "
                f"the house does not have; rooms: {sorted(labels)}"
            )
        lo = [_num(v) for v in inst.box.min]
        hi = [_num(v) for v in inst.box.max]
        attrs = inst.attributes
        out[str(inst.id)] = {
            "category": inst.category,
            # From the rounded box, so that a re-export of the imported house is identical.
            "position": [_num((a + b) / 2.0) for a, b in zip(lo, hi, strict=True)],
            "min_points": lo,
            "max_points": hi,
            "scope": scopes.get(inst.room_id, _scope(house, 0)),
            "room": labels.get(inst.room_id, ""),
            "region_id": inst.room_id,
            "unique_description": {
                FINE_CATEGORY_KEY: inst.fine_category,
                **{key: getattr(attrs, key) for key in DESCRIPTION_KEYS},
            },
            "nearby_objects": {
                other: words[0] if len(words) == 1 else words
                for other, words in nearby.get(inst.id, {}).items()
            },
            "caption": inst.caption,
        }
    return out


def _scope(house: House, level: int) -> str:
    """A floor's scope: the house's name, with ``_<level>`` when it has several floors."""
    several = len({room.level for room in house.rooms}) > 1
    return f"{house.name}_{level}" if several else house.name


def _region_dict(house: House) -> dict[str, Any]:
    """One scope per floor, floors in order, rooms in id order within each."""
    out: dict[str, Any] = {_scope(house, k): [] for k in sorted({r.level for r in house.rooms})}
    for room in sorted(house.rooms, key=lambda r: r.id):
        grown = _plan_points(grown_polygon(room.polygon, ENLARGE_MARGIN))
        region = {"label": _room_label(room), "id": room.id, "poly": _plan_points(room.polygon)}
        out[_scope(house, room.level)].append({**region, "enlarge_poly": grown})
    return out or {house.name: []}


# A list of numbers that json.dumps spread over lines (raw newlines never occur in strings).
_SPREAD_NUMBERS = re.compile(r"\[\n *(-?[0-9][-+.0-9eE]*(?:,\n *-?[0-9][-+.0-9eE]*)*)\n *\]")


def _to_json(data: dict[str, Any]) -> str:
    """Two-space indented JSON with each list of numbers (a point) on one line."""
    text = json.dumps(data, indent=2, ensure_ascii=False, allow_nan=False)
    return _SPREAD_NUMBERS.sub(_one_line, text) + "\n"


def _one_line(match: re.Match[str]) -> str:
    return "[" + ", ".join(number.strip() for number in match[1].split(",")) + "]"
