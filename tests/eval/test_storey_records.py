"""Episodes that climb stairs: their records carry heights, and maps and videos follow them."""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import av
import numpy as np
import pytest
from PIL import Image

from vlln.agents.registry import make_agent
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.episode_map import draw_episode_map, pose_storeys
from vlln.eval.play import play_episode
from vlln.eval.video import VideoConfig, map_images, replay
from vlln.eval.videos import write_videos
from vlln.tasks.env import NavigationEnv
from vlln.tasks.generation import generate_house_episodes
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache, procedural_house, procedural_scene_id
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.world.generator import HouseParameters, generate_house

SCENE = procedural_scene_id(76, 2)


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    cache = SceneCache(capacity=1)
    yield cache
    cache.close()


@pytest.fixture(scope="module")
def climb(scenes: SceneCache) -> EpisodeRecord:
    """The expert's record of an IGN episode whose target is on the other storey."""
    sim = scenes.get(SCENE)
    storeys = sim.storeys
    assert storeys is not None
    made = generate_house_episodes(sim, np.random.default_rng(0))
    episode = next(
        e
        for e in made.ign
        if storeys.level_of(e.start_position[1])
        != storeys.level_under(sim.house.instance(int(e.instruction.instance_id[0])).box.min[1])
    )
    env = NavigationEnv([episode], TaskConfig(task=TaskType.IGN), scenes, privileged=True)
    return play_episode(env, make_agent("expert", seed=0), "expert")


@pytest.mark.slow
def test_a_climbing_record_holds_the_height_of_every_pose(
    climb: EpisodeRecord, scenes: SceneCache
) -> None:
    sim = scenes.get(SCENE)
    assert sim.storeys is not None
    assert climb.end_reason == "stop" and climb.geodesic_final < 0.25
    assert len(climb.heights) == len(climb.positions)
    floors = sim.storeys.floor_ys
    assert {climb.heights[0], climb.heights[-1]} == {floors[0], floors[1]}
    between = [y for y in climb.heights if floors[0] < y < floors[1]]
    assert between, "the heights follow the treads on the way"
    again = EpisodeRecord.from_json(json.loads(json.dumps(climb.to_json())))
    assert again.heights == climb.heights


def test_one_storey_records_have_no_heights_in_their_json(climb: EpisodeRecord) -> None:
    flat = replace(climb, heights=[])
    assert "heights" not in flat.to_json()
    assert EpisodeRecord.from_json(flat.to_json()) == flat
    broken = dict(climb.to_json(), heights=climb.heights[:-1])
    with pytest.raises(DataFormatError, match="one height per position"):
        EpisodeRecord.from_json(broken)


def test_a_scene_id_with_storeys_names_that_house() -> None:
    assert procedural_house(SCENE).rooms == generate_house(76, HouseParameters(floors=2)).rooms
    assert len({room.level for room in procedural_house(procedural_scene_id(76)).rooms}) == 1


def test_the_replay_puts_the_camera_at_the_recorded_heights(
    climb: EpisodeRecord, scenes: SceneCache
) -> None:
    sim = scenes.get(SCENE)
    heights = [step.state.position[1] for step in replay(climb, sim)]
    assert set(heights) == set(climb.heights)
    with pytest.raises(ConfigError, match="no heights"):
        list(replay(replace(climb, heights=[]), sim))


def test_the_episode_map_has_a_panel_per_storey_with_its_part_of_the_trail(
    climb: EpisodeRecord, scenes: SceneCache, tmp_path: Path
) -> None:
    house = scenes.get(SCENE).house
    levels = pose_storeys(climb, house)
    assert levels is not None and levels[0] != levels[-1]
    path = tmp_path / "map.png"
    draw_episode_map(climb, house, path, "climb")
    image = np.asarray(Image.open(path).convert("RGB")).astype(int)
    trail = (abs(image - (0x1F, 0x3F, 0xBF)).sum(axis=2) < 60).any(axis=0)
    half = image.shape[1] // 2
    assert trail[:half].any() and trail[half:].any(), "the trail is on both storeys' panels"


@pytest.mark.slow
def test_the_video_map_switches_storey_with_the_agent(
    climb: EpisodeRecord, scenes: SceneCache, tmp_path: Path
) -> None:
    [(path, _)] = write_videos([climb], tmp_path)
    with av.open(str(path)) as container:
        frames = [frame.to_ndarray(format="rgb24") for frame in container.decode(video=0)]
    house = scenes.get(SCENE).house
    plans, _ = map_images(house, climb, VideoConfig().map_size)
    levels = pose_storeys(climb, house)
    assert levels is not None

    def nearest_plan(frame: np.ndarray) -> int:
        panel = frame[: VideoConfig().map_size, 640:].astype(int)
        return min(plans, key=lambda storey: np.abs(panel - plans[storey]).mean())

    assert [nearest_plan(frames[0]), nearest_plan(frames[-1])] == [levels[0], levels[-1]]
