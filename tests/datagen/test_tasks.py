"""Building IGN data by the shortest path and ObjectNav data by exploration (no dialog for
either), exporting them mixed for co-training, and balancing a built dataset."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import pytest

from vlln.cli import main
from vlln.datagen.build import BuildConfig, Strategy, check_settings, recorded_strategy
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.errors import ConfigError
from vlln.sim.agent import Action
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.generation import episode_config


def build(out: Path, episodes: Path, *flags: str) -> Path:
    """``vlln data build`` of the train split's first house; its episode files (stage 2, the
    same for every task and policy) are copied from ``episodes``, a build of that house."""
    shutil.copytree(episodes, out / "episodes")
    command = ["data", "build", "--houses", "1", "--per-house", "3", "--preset", "small", "--quiet"]
    assert main([*command, *flags, "--out", str(out)]) == 0
    return out


@pytest.fixture(scope="module")
def ign_shortest(tmp_path_factory: pytest.TempPathFactory, one_house_dataset: Path) -> Path:
    folder, episodes = tmp_path_factory.mktemp("ign"), one_house_dataset / "episodes"
    return build(folder, episodes, "--task", "ign", "--policy", "shortest")


@pytest.fixture(scope="module")
def objectnav(tmp_path_factory: pytest.TempPathFactory, one_house_dataset: Path) -> Path:
    folder, episodes = tmp_path_factory.mktemp("objectnav"), one_house_dataset / "episodes"
    return build(folder, episodes, "--task", "objectnav")


def rows(dataset: Path) -> list[tuple[HouseDataset, dict]]:
    houses = [HouseDataset(folder) for folder in house_folders(dataset)]
    found = [(house, row) for house in houses for row in house.episodes]
    assert found, "the build kept no trajectory"
    return found


def episodes_by_id(dataset: Path, task: str) -> dict[str, Episode]:
    return {e.episode_id: e for e in read_episodes(dataset / "episodes" / f"train_{task}.json.gz")}


def test_the_task_and_policy_are_recorded_unless_first() -> None:
    assert {"task", "policy", "floors"}.isdisjoint(BuildConfig(houses=1).to_json())
    settings = BuildConfig(houses=1, task="ign", policy="shortest").settings()
    assert (settings["task"], settings["policy"]) == ("ign", "shortest")
    with pytest.raises(ConfigError, match=r"^task: "):
        BuildConfig.build({"houses": 1, "task": "vln"}, flags=False)


def test_a_folder_built_before_tasks_resumes_as_iign_frontier(tmp_path: Path) -> None:
    """An older build.json has no task or policy: the default build resumes it, another
    task is refused by name."""
    check_settings(tmp_path, BuildConfig(houses=1))
    recorded = json.loads((tmp_path / "build.json").read_text())
    assert "task" not in recorded and "policy" not in recorded
    check_settings(tmp_path, BuildConfig(houses=1))
    with pytest.raises(ConfigError, match="differing: task"):
        check_settings(tmp_path, BuildConfig(houses=1, task="objectnav"))


def test_the_preset_is_recorded_and_defaults_to_the_benchmarks_houses(tmp_path: Path) -> None:
    """A build walks mp3d houses unless told, as evaluation scores on them, and says so in
    build.json; its episodes are drawn as the preset's evaluation splits draw them."""
    mp3d = BuildConfig(houses=1)
    assert (
        mp3d.settings()["preset"] == "mp3d" and mp3d.scene_id(3) == "vlln/mp3d_00003/mp3d_00003.glb"
    )
    assert mp3d.episodes == episode_config("mp3d") != BuildConfig(houses=1, preset="small").episodes
    with pytest.raises(ConfigError, match="--floors sets the storeys of small houses"):
        BuildConfig.build({"houses": 1, "floors": 2})
    check_settings(tmp_path, BuildConfig(houses=1, preset="small"))
    assert json.loads((tmp_path / "build.json").read_text())["preset"] == "small"
    assert recorded_strategy(tmp_path) == Strategy("small", "iign", "frontier")


def test_a_folder_built_before_presets_resumes_as_small_houses(tmp_path: Path) -> None:
    """An older build.json has no preset: its houses were small, and an mp3d build of the
    same folder is refused by name."""
    settings = BuildConfig(houses=1, preset="small").settings()
    del settings["preset"]
    (tmp_path / "build.json").write_text(json.dumps(settings))
    check_settings(tmp_path, BuildConfig(houses=1, preset="small"))
    assert recorded_strategy(tmp_path) == Strategy("small", "iign", "frontier")
    with pytest.raises(ConfigError, match="differing: episodes, preset"):
        check_settings(tmp_path, BuildConfig(houses=1))


@pytest.mark.slow
def test_ign_shortest_path_walks_straight_to_the_target_without_dialog(
    ign_shortest: Path,
) -> None:
    settings = json.loads((ign_shortest / "build.json").read_text())
    assert (settings["task"], settings["policy"]) == ("ign", "shortest")
    episodes = episodes_by_id(ign_shortest, "ign")
    for house, row in rows(ign_shortest):
        assert house.info["generator"]["task"] == "ign"
        assert house.info["generator"]["policy"] == "shortest"
        episode = episodes[row["episode_id"]]
        assert row["dialogs"] == [] and row["path_node_to_frame"] == []
        assert row["tasks"] == [episode.instruction.instruction_text]  # the full description
        actions = house.frames(row["episode_index"])["action"].tolist()
        assert actions[1:13] != [int(Action.TURN_LEFT)] * 12  # no opening scan
        # the shortest path on the lattice: little longer than the geodesic distance
        assert row["path_length"] <= 1.25 * row["geodesic_distance"] + 0.5


@pytest.mark.slow
def test_objectnav_stops_at_an_instance_of_the_category_without_dialog(objectnav: Path) -> None:
    settings = json.loads((objectnav / "build.json").read_text())
    assert settings["task"] == "objectnav" and "policy" not in settings
    episodes = episodes_by_id(objectnav, "objectnav")
    for house, row in rows(objectnav):
        episode = episodes[row["episode_id"]]
        assert row["dialogs"] == []
        assert row["target"]["instance_id"] in episode.instruction.instance_id
        assert row["target"]["category"] == episode.object_category
        # the distance is to the nearest instance's view points, as the episode records it
        assert math.isclose(
            row["geodesic_distance"], episode.info["geodesic_distance"], abs_tol=0.06
        )
        actions = house.frames(row["episode_index"])["action"].tolist()
        assert actions[1:13] == [int(Action.TURN_LEFT)] * 12  # frontier: the opening scan


@pytest.mark.slow
def test_export_mixes_the_tasks_and_records_the_mix(
    ign_shortest: Path, objectnav: Path, tmp_path: Path
) -> None:
    out = tmp_path / "sft"
    command = ["data", "export-sft", str(ign_shortest), str(objectnav), "--out", str(out)]
    assert main([*command, "--quiet"]) == 0
    document = json.loads((out / "export.json").read_text())
    mix = document["datasets"]
    assert [(d["tag"], d["task"], d["policy"]) for d in mix] == [
        ("ign", "ign", "shortest"),
        ("objectnav", "objectnav", "frontier"),
    ]
    for entry, dataset in zip(mix, (ign_shortest, objectnav), strict=True):
        assert entry["trajectories"] == len(rows(dataset))
        assert document["counts_by_task"][entry["task"]]["samples"] == entry["samples"] > 0
    lines = [json.loads(line) for line in (out / "sft.jsonl").read_text().splitlines()]
    assert len(lines) == document["counts"]["samples"]
    assert document["counts"]["samples_by_kind"]["dialog"] == 0
    for tag in ("ign", "objectnav"):
        mine = [line for line in lines if line["id"].startswith(f"{tag}/house_")]
        assert len(mine) == next(d["samples"] for d in mix if d["tag"] == tag)
        assert all(path.startswith(f"images/{tag}/") for line in mine for path in line["images"])
    assert all((out / path).is_file() for line in lines for path in line["images"])
    assert not any("<talk>" in turn["value"] for line in lines for turn in line["conversations"])


@pytest.mark.slow
def test_a_balanced_dataset_is_exported_like_a_built_one(
    objectnav: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    balanced = tmp_path / "balanced"
    command = ["data", "balance", str(objectnav), "--out", str(balanced), "--per-scene", "1"]
    assert main([*command, "--quiet"]) == 0
    settings = json.loads((balanced / "build.json").read_text())
    assert settings["task"] == "objectnav"
    assert settings["balance"]["caps"]["scene"] == 1 and settings["balance"]["kept"] == 1
    [(house, row)] = rows(balanced)
    source = HouseDataset(objectnav / "trajectories" / house.root.name)
    assert row in source.episodes
    assert house.info["total_episodes"] == 1 and house.info["balanced_from"] == len(source.episodes)
    assert (balanced / "balance" / "report.md").read_text().count("→") >= 4
    assert (balanced / "balance" / "histograms.png").stat().st_size > 10_000
    out = tmp_path / "sft"
    assert main(["data", "export-sft", str(balanced), "--out", str(out), "--quiet"]) == 0
    assert json.loads((out / "export.json").read_text())["counts"]["trajectories"] == 1
    capsys.readouterr()
    assert main([*command, "--quiet"]) != 0
    assert "not an empty folder; choose a new --out" in capsys.readouterr().err
    rebuild = ["data", "build", "--houses", "1", "--per-house", "3", "--preset", "small"]
    rebuild += ["--task", "objectnav"]
    assert main([*rebuild, "--out", str(balanced), "--quiet"]) != 0
    assert "other settings (differing: balance;" in capsys.readouterr().err
