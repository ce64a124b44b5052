"""Tests of the episode records and the released episode file format."""

from __future__ import annotations

import copy
import dataclasses
import gzip
import json
from pathlib import Path
from typing import Any

import pytest

from vlln.errors import DataFormatError
from vlln.tasks.episode import (
    Episode,
    Goal,
    Instruction,
    ViewPoint,
    read_episodes,
    write_episodes,
)


def make_episode(index: int, info: dict[str, Any] | None = None) -> Episode:
    target = Goal(
        position=(1.5, 0.4, -2.25),
        radius=0.6,
        bbox=(1.0, 0.0, -2.5, 2.0, 0.8, -2.0),
        view_points=(ViewPoint((0.75, 0.0, -2.0)), ViewPoint((2.5, 0.0, -1.75))),
    )
    distractor = Goal((4.0, 0.4, 1.0), None, (3.5, 0.0, 0.5, 4.5, 0.8, 1.5), ())
    return Episode(
        episode_id=str(index),
        scene_id=f"house_{index:04d}/house_{index:04d}.glb",
        start_position=(0.1 * index, 0.0, 3.0),
        start_rotation=(0.0, 0.7071, 0.0, 0.7071),
        object_category="couch",
        goals=(target, distractor),
        instruction=Instruction(
            task_type="ign",
            instruction_text="Find the grey sofa next to the lamp.",
            instance_id=("12",),
            instruction_info=("color",) if index % 2 else None,
        ),
        info=info or {},
    )


def write_raw(path: Path, data: Any) -> Path:
    path.write_bytes(gzip.compress(json.dumps(data).encode("utf-8")))
    return path


def raw_episode() -> dict[str, Any]:
    return make_episode(3).to_json()


def test_round_trip_gives_equal_records_and_identical_bytes(tmp_path: Path) -> None:
    episodes = [make_episode(i) for i in range(4)] + [make_episode(9, {"difficulty": "hard"})]
    first = tmp_path / "val_ign.json.gz"
    write_episodes(first, episodes)
    back = read_episodes(first)
    assert back == episodes
    second = tmp_path / "again" / "val_ign.json.gz"
    write_episodes(second, back)
    assert second.read_bytes() == first.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["again", "val_ign.json.gz"]


def test_file_layout_matches_the_released_format(tmp_path: Path) -> None:
    path = tmp_path / "e.json.gz"
    write_episodes(path, [make_episode(1), make_episode(2, {"seed": 5})])
    raw = path.read_bytes()
    assert raw[:2] == b"\x1f\x8b" and raw[4:8] == b"\x00\x00\x00\x00"  # gzip, mtime 0
    data = json.loads(gzip.decompress(raw))
    assert list(data) == ["episodes"]
    one, two = data["episodes"]
    assert list(one) == [
        "episode_id",
        "scene_id",
        "start_position",
        "start_rotation",
        "object_category",
        "goals",
        "instruction",
    ]
    assert two["info"] == {"seed": 5}
    assert one["goals"][0]["view_points"][1] == {"agent_state": {"position": [2.5, 0.0, -1.75]}}
    assert one["goals"][1]["radius"] is None
    assert one["instruction"] == {
        "task_type": "ign",
        "instruction_text": "Find the grey sofa next to the lamp.",
        "instance_id": ["12"],
        "instruction_info": ["color"],
    }
    assert two["instruction"]["instruction_info"] is None


def test_an_earlier_category_name_reads_as_the_catalogue_name(tmp_path: Path) -> None:
    episode = raw_episode()
    episode["object_category"] = "sofa"
    (back,) = read_episodes(write_raw(tmp_path / "e.json.gz", {"episodes": [episode]}))
    assert back.object_category == "couch"
    del episode["object_category"]
    episode["goals"][0]["object_category"] = "trash can"
    (back,) = read_episodes(write_raw(tmp_path / "g.json.gz", {"episodes": [episode]}))
    assert back.object_category == "garbage"


def test_reads_integers_nulls_and_the_accepted_extras(tmp_path: Path) -> None:
    episode = raw_episode()
    episode["start_position"] = [1, 0, 2]
    episode["info"] = None
    del episode["instruction"]["instruction_info"]
    data = {"episodes": [episode], "category_to_task_category_id": {"sofa": 3}}
    (back,) = read_episodes(write_raw(tmp_path / "e.json.gz", data))
    assert back.start_position == (1.0, 0.0, 2.0)
    assert isinstance(back.start_position[0], float)
    assert back.info == {}
    assert back.instruction.instruction_info is None


def test_an_empty_episode_list_round_trips(tmp_path: Path) -> None:
    path = tmp_path / "none.json.gz"
    write_episodes(path, [])
    assert read_episodes(path) == []


def mutated(change: str) -> dict[str, Any]:
    """A valid episode with one thing broken, described by ``change``."""
    episode = copy.deepcopy(raw_episode())
    goal = episode["goals"][0]
    match change:
        case "unknown key":
            episode["difficulty"] = []
        case "unknown goal key":
            goal["colour"] = 4
        case "missing key":
            del episode["scene_id"]
        case "missing instruction key":
            del episode["instruction"]["instance_id"]
        case "wrong type":
            episode["episode_id"] = 3.5
        case "wrong list type":
            episode["instruction"]["instance_id"] = [[12]]
        case "bool number":
            episode["start_position"] = [True, 0.0, 1.0]
        case "wrong length":
            goal["bbox"] = [0.0, 0.0, 0.0, 1.0, 1.0]
        case "rotation length":
            episode["start_rotation"] = [0.0, 0.0, 1.0]
        case "view point position":
            goal["view_points"][1]["agent_state"]["position"] = [1.0, 2.0]
        case "empty goals":
            episode["goals"] = []
        case "not finite":
            goal["radius"] = float("inf")
    return episode


@pytest.mark.parametrize(
    ("change", "field", "expected"),
    [
        ("unknown key", "difficulty", "only the keys"),
        ("unknown goal key", "goals[0].colour", "only the keys"),
        ("missing key", "scene_id", "got no such key"),
        ("missing instruction key", "instruction.instance_id", "got no such key"),
        ("wrong type", "episode_id", "a string or an integer"),
        ("wrong list type", "instruction.instance_id[0]", "a string or an integer"),
        ("bool number", "start_position", "a list of 3 finite numbers"),
        ("wrong length", "goals[0].bbox", "a list of 6 finite numbers"),
        ("rotation length", "start_rotation", "a list of 4 finite numbers"),
        ("view point position", "goals[0].view_points[1].agent_state.position", "3 finite"),
        ("empty goals", "goals", "a non-empty list of goals"),
        ("not finite", "goals[0].radius", "finite numbers"),
    ],
)
def test_errors_name_file_episode_field_and_expectation(
    tmp_path: Path, change: str, field: str, expected: str
) -> None:
    good = raw_episode()
    path = write_raw(tmp_path / "bad.json.gz", {"episodes": [good, mutated(change)]})
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message.startswith(f"{path}: episode 1 (episode_id ")
    assert f"field {field!r}" in message
    assert expected in message


def test_rejects_files_that_are_not_gzip_json_episode_lists(tmp_path: Path) -> None:
    plain = tmp_path / "plain.json.gz"
    plain.write_text('{"episodes": []}', encoding="utf-8")
    with pytest.raises(DataFormatError, match="is not a gzip file"):
        read_episodes(plain)
    truncated = tmp_path / "truncated.json.gz"
    truncated.write_bytes(gzip.compress(b'{"episodes": []}')[:12])
    with pytest.raises(DataFormatError, match="is not a gzip file"):
        read_episodes(truncated)
    not_json = tmp_path / "text.json.gz"
    not_json.write_bytes(gzip.compress(b"episodes: []"))
    with pytest.raises(DataFormatError, match="does not hold UTF-8 JSON"):
        read_episodes(not_json)
    with pytest.raises(DataFormatError, match="does not exist"):
        read_episodes(tmp_path / "missing.json.gz")
    for data, message in [
        ([], "expected a JSON object with an 'episodes' list"),
        ({"episodes": {}}, "'episodes' must be a list"),
        ({"episodes": [7]}, r"episode 0 \(episode_id None\): .*a JSON object"),
    ]:
        path = write_raw(tmp_path / "x.json.gz", data)
        with pytest.raises(DataFormatError, match=message):
            read_episodes(path)


def test_write_refuses_what_read_would_reject(tmp_path: Path) -> None:
    path = tmp_path / "out.json.gz"
    no_goals = dataclasses.replace(make_episode(1), goals=())
    with pytest.raises(DataFormatError, match=r"episode 0 .*field 'goals'"):
        write_episodes(path, [no_goals])
    nan_start = dataclasses.replace(make_episode(1), start_position=(float("nan"), 0.0, 0.0))
    with pytest.raises(DataFormatError, match="cannot write episodes"):
        write_episodes(path, [nan_start])
    with pytest.raises(DataFormatError, match="cannot write episodes"):
        write_episodes(path, [make_episode(1, {"when": object()})])
    assert not path.exists()
    assert list(tmp_path.iterdir()) == []
