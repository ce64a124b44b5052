"""Training data on houses with two storeys, and one-storey data as it always was."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tests.datagen.digest import content_digest
from vlln.cli import main
from vlln.datagen.build import BuildConfig, build_house, check_settings, prepare_episodes
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.errors import ConfigError
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache
from vlln.tasks.splits import house_seeds

TWO_STOREYS = BuildConfig(houses=1, per_house=1, floors=2, preset="small")
CAMERA_HEIGHT = 1.25
# What `BuildConfig(houses=2, per_house=1, preset="small")` writes on one-storey houses (the
# settings list the map's `below_floor` and `stair_step`, and the preset; each episode's
# oracle is eval's default, seeded as vlln eval seeds it; pixel goals are kept where the
# follower walks the teacher's steps). A deliberate change to the houses, episodes or
# collector changes it: then record the new digest.
ONE_STOREY_DIGEST = "4fd61c8c5a1eda4cb4e353578caf3c2a2f6e1e27488640d6d3dd759ec982d00f"


def _climbs_from_floor_to_floor(episode: Episode, floors: tuple[float, ...]) -> bool:
    """Start and every view point on a storey's floor (not on the stairs), on two storeys."""
    view_ys = {vp.position[1] for vp in episode.goals[0].view_points}
    start_y = episode.start_position[1]
    return start_y in floors and view_ys <= set(floors) and start_y not in view_ys


@pytest.fixture(scope="module")
def climbing(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The build's stages on one two-storey house, for its nearest episode whose target is
    on the other storey (start and view points off the stairs)."""
    root = tmp_path_factory.mktemp("storeys")
    check_settings(root, TWO_STOREYS)
    seeds = house_seeds(TWO_STOREYS.split, TWO_STOREYS.houses)
    scene_id = TWO_STOREYS.scene_id(seeds[0])
    cache = SceneCache(capacity=1)
    try:
        episodes = prepare_episodes(root, TWO_STOREYS, seeds, cache, False)[scene_id]
        sim = cache.get(scene_id)
        assert sim.storeys is not None
        floors = sim.storeys.floor_ys
        nearest = min(
            (e for e in episodes if _climbs_from_floor_to_floor(e, floors)),
            key=lambda e: (float(e.info["geodesic_distance"]), e.episode_id),
        )
        build_house(root, sim, [nearest], TWO_STOREYS, False)
    finally:
        cache.close()
    return root


@pytest.mark.slow
def test_a_kept_trajectory_climbs_to_the_targets_storey(climbing: Path) -> None:
    (folder,) = house_folders(climbing)
    assert folder.name.endswith("_2f")
    data = HouseDataset(folder)
    assert data.info["total_episodes"] == 1, data.info["rejections"]
    frames = data.frames(0)
    heights = frames["pose.125cm_0deg"][:, 2, 3]  # z is up in the poses
    floors = {round(h - CAMERA_HEIGHT, 3) for h in (heights[0], heights[-1])}
    assert floors == {0.0, 2.8}  # starts on one storey's floor, ends on the other's
    between = heights[(heights > heights.min() + 0.01) & (heights < heights.max() - 0.01)]
    assert between.size >= 10  # on the treads, step by step
    steps = np.abs(np.diff(heights))
    assert steps.max() < 0.3  # never a jump of a storey
    level_and_down = frames["pose.125cm_30deg"][:, 2, 3]
    assert np.allclose(level_and_down, heights)  # both cameras at the agent's height
    settings = json.loads((climbing / "build.json").read_text(encoding="utf-8"))
    assert settings["floors"] == 2


@pytest.mark.slow
def test_stats_and_export_read_the_two_storey_data(
    climbing: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["data", "stats", str(climbing), "--out", str(tmp_path / "stats")]) == 0
    stats = json.loads((tmp_path / "stats" / "stats.json").read_text(encoding="utf-8"))
    assert "kept" in json.dumps(stats)
    sft = tmp_path / "sft"
    assert main(["data", "export-sft", str(climbing), "--out", str(sft), "--quiet"]) == 0
    assert "conversations from 1 trajectories" in capsys.readouterr().out
    assert (sft / "sft.jsonl").stat().st_size > 0


@pytest.mark.slow
def test_one_storey_data_is_what_it_was(small_dataset: Path) -> None:
    settings = json.loads((small_dataset / "build.json").read_text(encoding="utf-8"))
    assert "floors" not in settings
    assert content_digest(small_dataset) == ONE_STOREY_DIGEST


def test_storeys_outside_one_to_three_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(ConfigError, match=r"^--floors: must be one of 1, 2, 3, got 4$"):
        BuildConfig.build({"houses": 1, "floors": 4})
    build = [
        "data",
        "build",
        "--houses",
        "1",
        "--floors",
        "0",
        "--preset",
        "small",
        "--out",
        "unused",
        "--quiet",
    ]
    assert main(build) != 0
    error = capsys.readouterr().err.strip()
    assert error == "error: --floors: must be one of 1, 2, 3, got 0"
