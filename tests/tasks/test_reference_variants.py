"""Hand-made files in every variant the reference accepts (docs/reference-formats.md §1-§2)
load, and an evaluation runs on them against an imported scan."""

from __future__ import annotations

import copy
import gzip
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from vlln.eval.config import EvalConfig
from vlln.eval.runner import run_evaluation
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import read_episodes
from vlln.tasks.metrics import success
from vlln.tasks.scenes import SceneCache
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House
from vlln.world.scans import export_scene, load_scene
from vlln.world.scene_summary import import_scene_summary

SMALL = HouseParameters(min_rooms=3, max_rooms=4, min_area=35.0, max_area=55.0)
Variant = Callable[[dict[str, Any]], None]
START: list[tuple[float, float]] = []  # a navigable start, found once


@pytest.fixture(scope="module")
def scenes(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, House]:
    house = generate_house(7, SMALL)
    with Simulator(house) as sim:
        rng = np.random.default_rng(0)
        START.append(sim.grid.sample_navigable_point(rng, sim.grid.largest_component()))
    root = tmp_path_factory.mktemp("scenes")
    export_scene(house, root, "mp3d")
    (root / house.name / "object_dict.json").unlink()  # the scan's own annotations only
    (root / house.name / "region_dict.json").unlink()
    return root, house


def base_episode(house: House) -> dict[str, Any]:
    target = next(i for i in house.instances if i.category == "bed" or i.box.size[1] > 0.5)
    x, z = START[0]
    return {
        "episode_id": "1",
        "scene_id": f"mp3d/{house.name}/{house.name}.glb",
        "start_position": [x, 0.0, z],
        "start_rotation": [0.0, 0.0, 0.0, 1.0],
        "object_category": target.category,
        "goals": [
            {
                "position": list(target.box.center),
                "radius": None,
                "bbox": [*target.box.min, *target.box.max],
                "view_points": [],
            }
        ],
        "instruction": {
            "task_type": "ign",
            "instruction_text": f"Search for the {target.category}.",
            "instance_id": [str(target.id)],
            "instruction_info": [],
        },
    }


def _habitat_extras(e: dict[str, Any]) -> None:
    e.update(
        scene_dataset_config="mp3d.scene_dataset_config.json",
        additional_obj_config_paths=[],
        info={"geodesic_distance": 3.0},
        shortest_paths=None,
        start_room=None,
    )
    e["goals"][0].update(object_id=4, object_name="bed_4", room_id="2", room_name="bedroom")


def _frames(e: dict[str, Any]) -> None:
    e["frames"] = [{"frame": 0}]


def _no_radius_no_bbox(e: dict[str, Any]) -> None:
    del e["goals"][0]["radius"], e["goals"][0]["bbox"]


def _category_missing(e: dict[str, Any]) -> None:
    e["goals"][0]["object_category"] = e.pop("object_category")


def _category_null_from_text(e: dict[str, Any]) -> None:
    e["object_category"] = None


def _no_instruction_info(e: dict[str, Any]) -> None:
    del e["instruction"]["instruction_info"]


def _null_instruction_info(e: dict[str, Any]) -> None:
    e["instruction"]["instruction_info"] = None


def _integer_episode_id(e: dict[str, Any]) -> None:
    e["episode_id"] = 1


def _string_instance_id(e: dict[str, Any]) -> None:
    e["instruction"]["instance_id"] = [
        f"2/{e['object_category']}_{e['instruction']['instance_id'][0]}"
    ]


VARIANTS: dict[str, Variant] = {
    "habitat extras": _habitat_extras,
    "InternNav frames": _frames,
    "goal without radius or bbox": _no_radius_no_bbox,
    "object_category missing": _category_missing,
    "object_category null": _category_null_from_text,
    "instruction_info missing": _no_instruction_info,
    "instruction_info null": _null_instruction_info,
    "integer episode id": _integer_episode_id,
    "string instance id": _string_instance_id,
}


def write_file(path: Path, episodes: list[dict[str, Any]]) -> Path:
    data = {"episodes": episodes, "category_to_task_category": {"bed": 0}}
    path.write_bytes(gzip.compress(json.dumps(data).encode("utf-8")))
    return path


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_each_episode_variant_loads(name: str, scenes: tuple[Path, House], tmp_path: Path) -> None:
    _, house = scenes
    raw = base_episode(house)
    VARIANTS[name](raw)
    (episode,) = read_episodes(write_file(tmp_path / "val_ign.json.gz", [raw]))
    assert episode.episode_id == "1"
    assert episode.object_category == base_episode(house)["object_category"]
    target = house.instance_for_key(episode.instruction.instance_id[0])
    assert target.id == int(base_episode(house)["instruction"]["instance_id"][0])


@pytest.mark.slow
def test_an_evaluation_runs_on_every_variant_against_an_imported_scan(
    scenes: tuple[Path, House], tmp_path: Path
) -> None:
    root, house = scenes
    episodes = []
    for k, variant in enumerate(VARIANTS.values()):
        raw = copy.deepcopy(base_episode(house))
        variant(raw)
        raw["episode_id"] = k + 1
        episodes.append(raw)
    path = write_file(tmp_path / "val_ign.json.gz", episodes)
    config = EvalConfig(
        agent="expert", task="ign", split=None, episode_file=str(path), budgets=(0,)
    )
    cache = SceneCache(scenes_dir=root)
    try:
        outcome = run_evaluation(config, tmp_path / "run", progress=False, scenes=cache)
    finally:
        cache.close()
    assert outcome.complete and len(outcome.records) == len(VARIANTS)
    assert all(record.error is None for record in outcome.records)
    assert sum(success(record) for record in outcome.records) == len(VARIANTS)


def summary_files(folder: Path, objects: dict[str, Any], regions: dict[str, Any]) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "object_dict.json").write_text(json.dumps(objects), encoding="utf-8")
    (folder / "region_dict.json").write_text(json.dumps(regions), encoding="utf-8")
    return folder


SQUARE = [[0, 0], [4, 0], [4, -4], [0, -4]]
FAR_SQUARE = [[10, 0], [14, 0], [14, -4], [10, -4]]
REGIONS = {"s": [{"label": "resting region", "id": 0, "poly": SQUARE, "enlarge_poly": SQUARE}]}


def chair(**extra: Any) -> dict[str, Any]:
    return {
        "category": "chair",
        "position": [1, 0.4, 1],
        "min_points": [0.5, 0, 0.5],
        "max_points": [1.5, 0.8, 1.5],
        "scope": "s",
        "room": "resting region",
        **extra,
    }


def test_string_instance_ids(tmp_path: Path) -> None:
    house = import_scene_summary(summary_files(tmp_path / "s", {"3/chair_12": chair()}, REGIONS))
    assert [i.id for i in house.instances] == [12]
    assert house.instance_for_key("3/chair_12").category == "chair"


def test_integer_instance_and_region_ids(tmp_path: Path) -> None:
    regions = {"s": [{"label": "resting region", "id": "0", "poly": SQUARE}]}
    objects = {"7": chair(region_id=0, nearby_objects={8: "near"}), "8": chair()}
    house = import_scene_summary(summary_files(tmp_path / "s", objects, regions))
    assert [(i.id, i.room_id) for i in house.instances] == [(7, 0), (8, 0)]
    assert [(r.subject, r.object) for r in house.relations] == [(7, 8)]


@pytest.mark.parametrize("description", [None, "a red chair", {}])
def test_unique_description_missing_string_or_empty(tmp_path: Path, description: Any) -> None:
    entry = chair() if description is None else chair(unique_description=description)
    (inst,) = import_scene_summary(summary_files(tmp_path / "s", {"1": entry}, REGIONS)).instances
    assert inst.attributes.color == ""
    assert inst.caption == ("a red chair" if description == "a red chair" else "")


def test_nearby_objects_as_words_or_dicts(tmp_path: Path) -> None:
    objects = {
        "1": chair(nearby_objects={"2": "next to", "3": {"relation": "near", "distance": 0.5}}),
        "2": chair(),
        "3": chair(),
    }
    house = import_scene_summary(summary_files(tmp_path / "s", objects, REGIONS))
    assert [(r.subject, r.word, r.object) for r in house.relations] == [
        (1, "next to", 2),
        (1, "near", 3),
    ]


def test_several_scopes_and_two_rooms_sharing_a_label(tmp_path: Path) -> None:
    regions = {
        "floor0": [
            {"label": "resting region", "id": 0, "poly": SQUARE},
            {"label": "resting region", "id": 1, "poly": FAR_SQUARE},
        ],
        "floor1": [{"label": "cooking region", "id": 0, "poly": SQUARE}],
    }
    far = chair(scope="floor0", position=[12, 0.4, 2], min_points=[11.5, 0, 1.5])
    far["max_points"] = [12.5, 0.8, 2.5]
    objects = {
        "1": far,
        "2": chair(scope="floor1", room="cooking region"),
    }
    house = import_scene_summary(summary_files(tmp_path / "scene", objects, regions))
    assert [(r.id, r.type, r.level) for r in house.rooms] == [
        (0, "bedroom", 0),
        (1, "bedroom", 0),
        (2, "kitchen", 1),
    ]
    assert [i.room_id for i in house.instances] == [1, 2]
    assert house.name == "scene"


def test_an_imported_scan_with_its_summary_takes_the_summary_words(
    scenes: tuple[Path, House], tmp_path: Path
) -> None:
    _, house = scenes
    export_scene(house, tmp_path, "hm3d")
    back = load_scene(tmp_path / house.name)
    assert [i.attributes for i in back.instances] == [i.attributes for i in house.instances]
    assert [r.type for r in back.rooms] == [r.type for r in house.rooms]


def test_the_eval_command_finds_scenes_in_the_scenes_folder(
    scenes: tuple[Path, House], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from vlln.cli import main

    root, house = scenes
    path = write_file(tmp_path / "val_ign.json.gz", [base_episode(house)])
    args = ["eval", "--agent", "expert", "--task", "ign", "--episode-file", str(path)]
    assert main([*args, "--scenes", str(root), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    assert "| 100.0 |" in capsys.readouterr().out.replace("100.00", "100.0")
    assert main([*args, "--out", str(tmp_path / "other"), "--quiet"]) == 2
    assert "pass the folder of scanned scenes that holds house_00007/ (--scenes DIR)" in (
        capsys.readouterr().err
    )
