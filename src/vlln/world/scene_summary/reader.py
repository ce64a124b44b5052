"""Reading a scene summary in every variant the reference reads (docs/reference-formats.md §2)."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.model import (
    Attributes,
    Box3,
    House,
    ObjectInstance,
    Point2,
    Point3,
    Relation,
    Room,
)
from vlln.world.scene_summary.format import (
    DESCRIPTION_KEYS,
    FINE_CATEGORY_KEY,
    LABEL_TO_ROOM_TYPE,
    OBJECT_DICT_FILE,
    REGION_DICT_FILE,
    UNKNOWN_ROOM_ID,
)

# A released house's object_dict.json is at most a few MB; a bigger scan may raise the cap.
SCENE_SUMMARY_CAP = ReadCap("a scene-summary file", 64, "VLLN_MAX_SCENE_SUMMARY_MB")


def import_scene_summary(scene_dir: str | Path) -> House:
    """Read a scene-summary directory back into a :class:`House` without geometry.

    Every variant the reference reads is accepted (docs/reference-formats.md §2): several scopes
    (one per floor; rooms are then renumbered in scope order and get the scope's index as
    their level), instance ids as integers or strings like ``"3/chair_12"`` (kept in
    :attr:`House.instance_keys`; the trailing number is the instance id, else ids follow the
    file order), ``unique_description`` missing, empty or a plain string (then the caption
    when there is none), and ``nearby_objects`` values that are words or small dicts.
    """
    scene_dir = Path(scene_dir)
    region_path = scene_dir / REGION_DICT_FILE
    object_path = scene_dir / OBJECT_DICT_FILE
    scopes, rooms = _parse_regions(region_path, _load_json(region_path))
    instances, nearby, keys = _parse_objects(object_path, _load_json(object_path), scopes, rooms)
    return House(
        name=next(iter(scopes)) if len(scopes) == 1 else scene_dir.name,
        rooms=rooms,
        doors=[],
        instances=instances,
        relations=_relations_of(instances, nearby),
        instance_keys=keys,
    )


def _load_json(path: Path) -> Any:
    if not path.is_file():
        raise DataFormatError(
            f"{path} does not exist; a scene-summary directory holds {OBJECT_DICT_FILE} and "
            f"{REGION_DICT_FILE}"
        )
    data = SCENE_SUMMARY_CAP.read(path)
    try:
        return parse_json(data)
    except DataFormatError as err:
        raise DataFormatError(f"{path} is not UTF-8 JSON: {err}") from None


def _bad(path: Path, where: str, field: str, expected: str, got: Any) -> DataFormatError:
    shown = repr(got) if len(repr(got)) <= 80 else repr(got)[:77] + "..."
    return DataFormatError(f"{path}: {where}: field {field!r}: expected {expected}, got {shown}")


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def _int_id(value: Any) -> int | None:
    """An id given as an int or a decimal string, else None."""
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, str) and re.fullmatch(r"-?[0-9]+", value.strip()):
        return int(value)
    return None


def _point3(path: Path, where: str, entry: dict[str, Any], field: str) -> Point3:
    value = entry.get(field)
    if not (isinstance(value, list) and len(value) == 3 and all(map(_is_number, value))):
        raise _bad(path, where, field, "a list of 3 finite numbers", value)
    return (float(value[0]), float(value[1]), float(value[2]))


def _text(path: Path, where: str, entry: dict[str, Any], field: str) -> str:
    """A string field where missing or null means unknown (``""``)."""
    value = entry.get(field)
    if value is None:
        return ""
    if not isinstance(value, str):
        raise _bad(path, where, field, "a string", value)
    return value


# Per scope: the file's region id -> our room id.
_ScopeRooms = dict[str, dict[int, int]]


def _parse_regions(path: Path, data: Any) -> tuple[_ScopeRooms, list[Room]]:
    if not (isinstance(data, dict) and data):
        raise _bad(path, "top level", "scope", "an object with at least one scene scope", data)
    renumber = len(data) > 1
    scopes: _ScopeRooms = {}
    rooms: list[Room] = []
    for level, (scope, regions) in enumerate(data.items()):
        if not isinstance(regions, list):
            raise _bad(path, f"scope {scope!r}", "regions", "a list of regions", regions)
        own: dict[int, Room] = {}
        for index, region in enumerate(regions):
            room = _parse_region(path, f"scope {scope!r}: region {index}", region, level)
            if room.id in own:
                raise _bad(path, f"scope {scope!r}: region {index}", "id", "a unique id", room.id)
            own[room.id] = room
        scopes[scope] = {}
        for region_id in sorted(own):
            room_id = len(rooms) if renumber else region_id
            scopes[scope][region_id] = room_id
            rooms.append(replace(own[region_id], id=room_id))
    return scopes, rooms


def _parse_region(path: Path, where: str, region: Any, level: int) -> Room:
    if not isinstance(region, dict):
        raise _bad(path, where, "region", "an object", region)
    room_id = _int_id(region.get("id"))
    if room_id is None or room_id < 0:
        raise _bad(path, where, "id", "an integer >= 0", region.get("id"))
    where = f"{where} (id {room_id})"
    label = region.get("label")
    if label not in LABEL_TO_ROOM_TYPE:
        raise _bad(path, where, "label", f"one of {sorted(LABEL_TO_ROOM_TYPE)}", label)
    poly = region.get("poly")
    if not (
        isinstance(poly, list)
        and len(poly) >= 3
        and all(isinstance(p, list) and len(p) == 2 and all(map(_is_number, p)) for p in poly)
    ):
        raise _bad(path, where, "poly", "a list of at least 3 [x, -z] number pairs", poly)
    polygon = tuple((float(x) + 0.0, -float(minus_z) + 0.0) for x, minus_z in poly)
    return Room(id=room_id, type=LABEL_TO_ROOM_TYPE[label], polygon=polygon, level=level)


def _instance_ids(keys: list[str]) -> dict[str, int]:
    """Our id per file key: the key's own number (``"12"``, ``"3/chair_12"``), else the next
    id after the largest number, in file order."""
    numbers: dict[str, int] = {}
    for key in keys:
        tail = key.rsplit("_", 1)[-1].rsplit("/", 1)[-1].strip()
        if tail.isdecimal() and int(tail) >= 1:
            numbers[key] = int(tail)
    if len(set(numbers.values())) != len(numbers):
        numbers = {}  # the numbers are not unique: number by file order instead
    following = max(numbers.values(), default=0)
    ids: dict[str, int] = {}
    for key in keys:
        if key not in numbers:
            following += 1
        ids[key] = numbers.get(key, following)
    return ids


def _parse_objects(
    path: Path, data: Any, scopes: _ScopeRooms, rooms: list[Room]
) -> tuple[list[ObjectInstance], dict[int, list[tuple[str, str]]], dict[str, int]]:
    """The instances, per subject id its ``(object key, word)`` pairs in file order, and the
    file's instance keys that are not plain decimal ids."""
    if not isinstance(data, dict):
        raise _bad(path, "top level", "instances", "an object keyed by instance id", data)
    ids = _instance_ids([str(key) for key in data])
    instances: dict[int, ObjectInstance] = {}
    nearby: dict[int, list[tuple[str, str]]] = {}
    first_scope = next(iter(scopes))
    for key, entry in data.items():
        where = f"instance {key!r}"
        instance_id = ids[str(key)]
        if not isinstance(entry, dict):
            raise _bad(path, where, "instance", "an object", entry)
        category = entry.get("category")
        if not (isinstance(category, str) and category):
            raise _bad(path, where, "category", "a non-empty string", category)
        category = canonical_category(category)
        if "position" in entry:
            _point3(path, where, entry, "position")
        a = _point3(path, where, entry, "min_points")
        b = _point3(path, where, entry, "max_points")
        box = Box3(
            (min(a[0], b[0]), min(a[1], b[1]), min(a[2], b[2])),
            (max(a[0], b[0]), max(a[1], b[1]), max(a[2], b[2])),
        )
        scope = entry.get("scope", first_scope)
        if scope not in scopes:
            expected = f"a scope of {REGION_DICT_FILE}, one of {sorted(scopes)}"
            raise _bad(path, where, "scope", expected, scope)
        description = entry.get("unique_description")
        caption = _text(path, where, entry, "caption")
        if isinstance(description, str):
            caption = caption or description
        if not isinstance(description, dict):
            description = {}  # the released data has some instances without a description
        dwhere = f"{where}: unique_description"
        attributes = Attributes(
            **{k: _text(path, dwhere, description, k) for k in DESCRIPTION_KEYS}
        )
        scope_rooms = [room for room in rooms if room.id in scopes[scope].values()]
        instances[instance_id] = ObjectInstance(
            id=instance_id,
            category=category,
            fine_category=_text(path, dwhere, description, FINE_CATEGORY_KEY),
            attributes=attributes,
            caption=caption,
            box=box,
            room_id=_room_of(path, where, entry, scope_rooms, scopes[scope], box),
        )
        nearby[instance_id] = _nearby_of(path, where, entry)
    keys = {key: ids[key] for key in map(str, data) if key != str(ids[key])}
    relations = {
        subject: [(str(ids.get(other, other)), word) for other, word in pairs]
        for subject, pairs in nearby.items()
    }
    return [instances[key] for key in sorted(instances)], relations, keys


def _room_of(
    path: Path,
    where: str,
    entry: dict[str, Any],
    rooms: list[Room],
    region_ids: dict[int, int],
    box: Box3,
) -> int:
    label = _text(path, where, entry, "room")
    if label == "":
        return UNKNOWN_ROOM_ID
    if label not in LABEL_TO_ROOM_TYPE:
        raise _bad(path, where, "room", f"'' or one of {sorted(LABEL_TO_ROOM_TYPE)}", label)
    kind = LABEL_TO_ROOM_TYPE[label]
    candidates = [room for room in rooms if room.type == kind]
    if "region_id" in entry:
        region_id = _int_id(entry["region_id"])
        room_id = None if region_id is None else region_ids.get(region_id)
        if room_id is None or room_id not in {room.id for room in candidates}:
            ours = {room: region for region, room in region_ids.items()}
            expected = f"the id of a {label!r} region, one of {[ours[r.id] for r in candidates]}"
            raise _bad(path, where, "region_id", expected, entry["region_id"])
        return room_id
    if not candidates:
        return UNKNOWN_ROOM_ID
    centre = (box.center[0], box.center[2])
    return min(candidates, key=lambda room: (_distance_outside(centre, room.polygon), room.id)).id


def _distance_outside(point: Point2, polygon: tuple[Point2, ...]) -> float:
    """0 inside ``polygon`` (even-odd rule), else the distance from ``point`` to its boundary."""
    p = np.asarray(polygon, dtype=np.float64) - np.asarray(point, dtype=np.float64)
    q = np.roll(p, -1, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):  # horizontal edges never cross
        x_at_0 = p[:, 0] - p[:, 1] * (q[:, 0] - p[:, 0]) / (q[:, 1] - p[:, 1])
    if np.count_nonzero(((p[:, 1] > 0) != (q[:, 1] > 0)) & (x_at_0 > 0)) % 2 == 1:
        return 0.0
    edge = q - p
    t = np.clip(-np.sum(p * edge, axis=1) / np.maximum(np.sum(edge * edge, axis=1), 1e-18), 0, 1)
    return float(np.min(np.linalg.norm(p + t[:, None] * edge, axis=1)))


_RELATION_KEYS = ("relation", "spatial_relation", "relationship", "word")


def _nearby_of(path: Path, where: str, entry: dict[str, Any]) -> list[tuple[str, str]]:
    """``(other key, word)`` pairs; a value is a word, a list of words, or a small dict whose
    relation word is under one of :data:`_RELATION_KEYS`."""
    value = entry.get("nearby_objects")
    if value is None:
        return []
    if not isinstance(value, dict):
        raise _bad(path, where, "nearby_objects", "an object {instance id: relation}", value)
    pairs: list[tuple[str, str]] = []
    for key, words in value.items():
        field = f"nearby_objects[{key!r}]"
        if isinstance(words, dict):
            words = next((words[k] for k in _RELATION_KEYS if isinstance(words.get(k), str)), [])
        word_list = [words] if isinstance(words, str) else words
        if not (isinstance(word_list, list) and all(isinstance(w, str) for w in word_list)):
            raise _bad(path, where, field, "a relation word, a list of them or a dict", words)
        pairs.extend((str(key), word) for word in word_list if word)
    return pairs


def _relations_of(
    instances: list[ObjectInstance], nearby: dict[int, list[tuple[str, str]]]
) -> list[Relation]:
    """Relations in (subject, object) order; those naming an instance not in the file drop."""
    boxes = {inst.id: inst.box for inst in instances}
    relations = [
        Relation(subject, word, int(other), boxes[subject].distance_to(boxes[int(other)]))
        for subject, pairs in nearby.items()
        for other, word in pairs
        if other.isdecimal() and int(other) in boxes and int(other) != subject
    ]
    return sorted(relations, key=lambda r: (r.subject, r.object))
