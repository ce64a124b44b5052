"""Tests of the scene-summary export and import."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from vlln.errors import DataFormatError
from vlln.world.catalogue.registry import ROOM_TYPES
from vlln.world.model import Attributes, Box3, Door, House, ObjectInstance, Relation, Room
from vlln.world.relations import build_relations
from vlln.world.scene_summary import (
    ENLARGE_MARGIN,
    LABEL_TO_ROOM_TYPE,
    OBJECT_DICT_FILE,
    REGION_DICT_FILE,
    ROOM_TYPE_TO_LABEL,
    SPOKEN_ROOM_NAMES,
    UNKNOWN_ROOM_ID,
    export_scene_summary,
    grown_polygon,
    import_scene_summary,
)

LIVING = Room(1, "living room", ((0.0, 0.0), (5.0, 0.0), (5.0, 4.0), (0.0, 4.0)))
BEDROOM_A = Room(2, "bedroom", ((5.0, 0.0), (8.5, 0.0), (8.5, 4.0), (5.0, 4.0)))
BEDROOM_B = Room(4, "bedroom", ((8.5, 0.0), (12.0, 0.0), (12.0, 4.0), (8.5, 4.0)))
KITCHEN = Room(  # L-shaped, clockwise in (x, z)
    3, "kitchen", ((0.0, 4.0), (0.0, 8.0), (5.0, 8.0), (5.0, 6.0), (2.5, 6.0), (2.5, 4.0))
)


def instance(
    instance_id: int,
    category: str,
    lo: tuple[float, float, float],
    hi: tuple[float, float, float],
    room_id: int,
    attributes: Attributes | None = None,
    support_id: int | None = None,
) -> ObjectInstance:
    return ObjectInstance(
        id=instance_id,
        category=category,
        fine_category=f"small {category}",
        attributes=attributes or Attributes(color="white", material="wood", size="small"),
        caption=f"A {category} in the room.",
        box=Box3(lo, hi),
        room_id=room_id,
        support_id=support_id,
    )


def make_house() -> House:
    instances = [
        instance(1, "table", (1.0, 0.0, 1.0), (2.2, 0.75, 1.8), 1),
        instance(2, "cup", (1.5, 0.75, 1.2), (1.6, 0.8625, 1.3), 1, support_id=1),
        instance(3, "chair", (2.3, 0.0, 1.0), (2.8, 0.9, 1.5), 1, Attributes()),
        instance(4, "bed", (9.0, 0.0, 0.5), (10.6, 0.5, 2.5), 4),
        instance(5, "nightstand", (10.7, 0.0, 0.5), (11.2, 0.6, 1.0), 4),
        instance(10, "lamp", (6.0, 1.5, 1.0), (6.4, 1.7, 1.4), 2),
        instance(7, "fridge", (0.5, 0.0, 7.0), (1.3, 1.8, 7.7), 3),
        instance(8, "plant", (0.0, 0.0, 0.0), (0.4, 1.0, 0.4), UNKNOWN_ROOM_ID),
    ]
    instances[6] = dataclasses.replace(instances[6], caption='A fridge, "[1,\n2]" on its door.')
    relations = build_relations(instances)
    relations.append(Relation(4, "against", 5, 0.1))  # a second word for one pair
    return House(
        name="house_0007",
        rooms=[LIVING, BEDROOM_A, KITCHEN, BEDROOM_B],
        doors=[Door(1, 1, 2, (5.0, 2.0), 0.9, "z")],
        instances=instances,
        relations=relations,
        seed=7,
    )


def read_bytes(scene_dir: Path) -> tuple[bytes, bytes]:
    return (scene_dir / OBJECT_DICT_FILE).read_bytes(), (scene_dir / REGION_DICT_FILE).read_bytes()


def write_json(scene_dir: Path, objects: Any, regions: Any) -> Path:
    scene_dir.mkdir(parents=True, exist_ok=True)
    (scene_dir / OBJECT_DICT_FILE).write_text(json.dumps(objects), encoding="utf-8")
    (scene_dir / REGION_DICT_FILE).write_text(json.dumps(regions), encoding="utf-8")
    return scene_dir


def test_round_trip_keeps_every_field_the_format_carries(tmp_path: Path) -> None:
    house = make_house()
    first = export_scene_summary(house, tmp_path / "a")
    assert first == tmp_path / "a" / "house_0007"
    back = import_scene_summary(first)

    assert back.name == house.name
    assert back.geometry is None and back.doors == []
    assert back.rooms == sorted(house.rooms, key=lambda r: r.id)
    # Yaw and support ids are not in the format.
    assert back.instances == sorted(
        (dataclasses.replace(i, support_id=None) for i in house.instances), key=lambda i: i.id
    )
    by_id = {i.id: i.box for i in house.instances}
    expected = sorted(
        (
            Relation(r.subject, r.word, r.object, by_id[r.subject].distance_to(by_id[r.object]))
            for r in house.relations
        ),
        key=lambda r: (r.subject, r.object),
    )
    assert back.relations == expected

    second = export_scene_summary(back, tmp_path / "b")
    assert read_bytes(second) == read_bytes(first)


def test_export_is_byte_identical_and_leaves_no_temporary_files(tmp_path: Path) -> None:
    first = read_bytes(export_scene_summary(make_house(), tmp_path / "a"))
    scene_dir = export_scene_summary(make_house(), tmp_path / "b")
    assert read_bytes(scene_dir) == first
    export_scene_summary(make_house(), tmp_path / "b")  # overwrite in place
    assert sorted(p.name for p in scene_dir.iterdir()) == [OBJECT_DICT_FILE, REGION_DICT_FILE]
    for data in first:
        assert data.endswith(b"}\n")
        assert b"-0.0," not in data and b"-0.0\n" not in data


def test_object_dict_content(tmp_path: Path) -> None:
    scene_dir = export_scene_summary(make_house(), tmp_path)
    objects = json.loads((scene_dir / OBJECT_DICT_FILE).read_text(encoding="utf-8"))
    assert list(objects) == ["1", "2", "3", "4", "5", "7", "8", "10"]
    cup = objects["2"]
    assert list(cup) == [
        "category",
        "position",
        "min_points",
        "max_points",
        "scope",
        "room",
        "region_id",
        "unique_description",
        "nearby_objects",
        "caption",
    ]
    assert cup["position"] == pytest.approx([1.55, 0.8062, 1.25], abs=1e-4)
    assert cup["scope"] == "house_0007"
    assert cup["room"] == "living region"
    assert cup["unique_description"] == {
        "fine grained category": "small cup",
        "color": "white",
        "texture": "",
        "material": "wood",
        "shape": "",
        "placement": "",
        "size": "small",
    }
    assert cup["nearby_objects"]["1"] == "on"
    assert objects["1"]["nearby_objects"]["2"] == "under"
    assert objects["4"]["nearby_objects"]["5"] == ["next to", "against"]
    assert objects["4"]["room"] == "resting region" and objects["4"]["region_id"] == 4
    assert objects["8"]["room"] == ""


def test_region_dict_content(tmp_path: Path) -> None:
    scene_dir = export_scene_summary(make_house(), tmp_path)
    regions = json.loads((scene_dir / REGION_DICT_FILE).read_text(encoding="utf-8"))
    assert list(regions) == ["house_0007"]
    entries = regions["house_0007"]
    assert [e["id"] for e in entries] == [1, 2, 3, 4]
    assert [e["label"] for e in entries] == [
        "living region",
        "resting region",
        "cooking region",
        "resting region",
    ]
    living = entries[0]
    assert list(living) == ["label", "id", "poly", "enlarge_poly"]
    assert living["poly"] == [[0.0, 0.0], [5.0, 0.0], [5.0, -4.0], [0.0, -4.0]]
    m = ENLARGE_MARGIN
    expected = [[-m, m], [5.0 + m, m], [5.0 + m, -4.0 - m], [-m, -4.0 - m]]
    np.testing.assert_allclose(living["enlarge_poly"], expected, atol=1e-4)


@pytest.mark.parametrize("reverse", [False, True])
def test_grown_polygon_moves_every_edge_outward(reverse: bool) -> None:
    points = KITCHEN.polygon[::-1] if reverse else KITCHEN.polygon
    grown = grown_polygon(points, 0.5)
    expected = [(-0.5, 3.5), (-0.5, 8.5), (5.5, 8.5), (5.5, 5.5), (3.0, 5.5), (3.0, 3.5)]
    if reverse:
        expected = expected[::-1]
    np.testing.assert_allclose(grown, expected, atol=1e-12)


def test_label_tables_cover_every_room_type_and_label() -> None:
    assert set(ROOM_TYPES) <= set(ROOM_TYPE_TO_LABEL)
    assert len(LABEL_TO_ROOM_TYPE) == len(ROOM_TYPE_TO_LABEL) == 13
    assert set(SPOKEN_ROOM_NAMES) == set(LABEL_TO_ROOM_TYPE)
    assert ROOM_TYPE_TO_LABEL["toilet"] == "toliet region"
    assert LABEL_TO_ROOM_TYPE["stair region"] == "stairs"
    assert SPOKEN_ROOM_NAMES["other region"] == "area"


def test_import_tolerates_the_released_data_quirks(tmp_path: Path) -> None:
    square = [[8.5, 0.0], [12.0, 0.0], [12.0, -4.0], [8.5, -4.0]]
    regions = {
        "scan": [
            {"label": "resting region", "id": "0", "poly": [[5, 0], [8.5, 0], [8.5, -4], [5, -4]]},
            {"label": "resting region", "id": 6, "poly": square, "extra": 1},
        ]
    }
    base = {"category": "bed", "position": [10, 0.25, 1], "scope": "scan", "room": "resting region"}
    objects = {
        "3": {
            **base,
            "min_points": [9, 0, 0.5],
            "max_points": [11, 0.5, 1.5],
            "unique_description": "",  # not a dict
            "nearby_objects": {"4": ["near", ""], "99": "near"},  # 99 is not in the file
            "caption": None,
            "some_new_key": [1, 2],
        },
        "4": {
            **base,
            "min_points": [11.4, 0.6, 1.7],  # min and max swapped
            "max_points": [11.2, 0.0, 1.2],
            "unique_description": {"color": "", "material": "oak", "fine grained category": ""},
            "nearby_objects": {"3": "near"},
        },
        "5": {**base, "min_points": [5, 0, 1], "max_points": [5.5, 1, 2], "room": "cooking region"},
    }
    house = import_scene_summary(write_json(tmp_path / "scan", objects, regions))
    assert house.name == "scan"
    assert [r.id for r in house.rooms] == [0, 6]
    assert house.rooms[1].polygon == ((8.5, 0.0), (12.0, 0.0), (12.0, 4.0), (8.5, 4.0))
    bed, stand, other = house.instances
    assert bed.room_id == 6 and stand.room_id == 6  # found by position among bedrooms
    assert other.room_id == UNKNOWN_ROOM_ID  # no kitchen region in the scene
    assert bed.attributes == Attributes() and bed.fine_category == "" and bed.caption == ""
    assert stand.attributes == Attributes(material="oak")
    assert stand.box == Box3((11.2, 0.0, 1.2), (11.4, 0.6, 1.7))
    assert [(r.subject, r.word, r.object) for r in house.relations] == [
        (3, "near", 4),
        (4, "near", 3),
    ]
    assert house.relations[0].distance == pytest.approx(0.2)


def test_room_falls_back_to_the_nearest_region_of_its_label(tmp_path: Path) -> None:
    regions = {
        "s": [
            {"label": "living region", "id": 1, "poly": [[0, 0], [4, 0], [4, -4], [0, -4]]},
            {"label": "living region", "id": 2, "poly": [[6, 0], [9, 0], [9, -4], [6, -4]]},
        ]
    }
    box = {"min_points": [5.2, 0, 1], "max_points": [5.8, 1, 2], "position": [5.5, 0.5, 1.5]}
    objects = {"1": {"category": "door", "scope": "s", "room": "living region", **box}}
    house = import_scene_summary(write_json(tmp_path / "s", objects, regions))
    assert house.instances[0].room_id == 2  # 0.2 m from region 2, 1.2 m from region 1


REGIONS = {"s": [{"label": "living region", "id": 1, "poly": [[0, 0], [4, 0], [4, -4]]}]}
GOOD = {
    "category": "sofa",
    "position": [1, 0.4, 1],
    "min_points": [0.5, 0, 0.5],
    "max_points": [1.5, 0.8, 1.5],
    "scope": "s",
    "room": "living region",
}


@pytest.mark.parametrize(
    ("objects", "regions", "message"),
    [
        ({"7": {**GOOD, "position": [1, 2]}}, REGIONS, r"instance '7': field 'position'"),
        ({"7": {**GOOD, "max_points": [1, "a", 2]}}, REGIONS, r"'7': field 'max_points'"),
        ({"7": {**GOOD, "category": ""}}, REGIONS, r"instance '7': field 'category'"),
        ({"7": {**GOOD, "room": "attic"}}, REGIONS, r"instance '7': field 'room'"),
        ({"7": {**GOOD, "scope": "other"}}, REGIONS, r"instance '7': field 'scope'"),
        ({"7": {**GOOD, "region_id": 5}}, REGIONS, r"instance '7': field 'region_id'"),
        ({"7": {**GOOD, "caption": 3}}, REGIONS, r"instance '7': field 'caption'"),
        ({"7": {**GOOD, "nearby_objects": ["1"]}}, REGIONS, r"field 'nearby_objects'"),
        (
            {"7": {**GOOD, "unique_description": {"color": 5}}},
            REGIONS,
            r"instance '7': unique_description: field 'color'",
        ),
        ([GOOD], REGIONS, r"top level: field 'instances'"),
        ({}, {}, r"at least one scene scope"),
        ({}, {"s": [{"label": "attic", "id": 1, "poly": []}]}, r"region 0 \(id 1\): .*'label'"),
        ({}, {"s": [{"label": "living region", "id": "x"}]}, r"region 0: field 'id'"),
        (
            {},
            {"s": [{"label": "living region", "id": 1, "poly": [[0, 0], [1, 0]]}]},
            r"region 0 \(id 1\): field 'poly'",
        ),
    ],
)
def test_import_errors_name_file_entry_and_field(
    tmp_path: Path, objects: Any, regions: Any, message: str
) -> None:
    scene_dir = write_json(tmp_path / "s", objects, regions)
    with pytest.raises(DataFormatError, match=message) as info:
        import_scene_summary(scene_dir)
    assert str(scene_dir) in str(info.value)


def test_import_reports_missing_and_broken_files(tmp_path: Path) -> None:
    with pytest.raises(DataFormatError, match="does not exist"):
        import_scene_summary(tmp_path / "nowhere")
    scene_dir = write_json(tmp_path / "s", {}, REGIONS)
    (scene_dir / OBJECT_DICT_FILE).write_text("{not json", encoding="utf-8")
    with pytest.raises(DataFormatError, match=r"object_dict\.json is not UTF-8 JSON"):
        import_scene_summary(scene_dir)


def test_export_rejects_what_the_format_cannot_express(tmp_path: Path) -> None:
    house = make_house()
    attic = dataclasses.replace(house, rooms=[*house.rooms, Room(9, "attic", LIVING.polygon)])
    with pytest.raises(DataFormatError, match="room 9 has type 'attic'"):
        export_scene_summary(attic, tmp_path)
    lost = dataclasses.replace(house, rooms=house.rooms[1:])
    with pytest.raises(DataFormatError, match=r"instance 1 .* room 1"):
        export_scene_summary(lost, tmp_path)
    with pytest.raises(DataFormatError, match="house name"):
        export_scene_summary(dataclasses.replace(house, name="a/b"), tmp_path)
    nan_box = dataclasses.replace(
        house.instances[0], box=Box3((float("nan"), 0.0, 0.0), (1.0, 1.0, 1.0))
    )
    with pytest.raises(DataFormatError, match="non-finite"):
        export_scene_summary(dataclasses.replace(house, instances=[nan_box]), tmp_path)


def test_an_earlier_category_name_reads_as_the_catalogue_name(tmp_path: Path) -> None:
    house = import_scene_summary(write_json(tmp_path / "s", {"7": GOOD}, REGIONS))
    assert [inst.category for inst in house.instances] == ["couch"]
