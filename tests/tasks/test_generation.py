"""Tests of episode generation on small generated houses and of the split files."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import pytest

from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator
from vlln.tasks import generation, split_files
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.generation import (
    SKIP_REASONS,
    EpisodeGenConfig,
    HouseEpisodes,
    generate_house_episodes,
    house_rng,
)
from vlln.tasks.instructions import (
    AmbiguousTargetError,
    FullInstruction,
    InstructionWriter,
    matching_instances,
)
from vlln.tasks.scenes import SceneCache, procedural_scene_id, procedural_seed
from vlln.tasks.spec import TaskType
from vlln.tasks.split_files import (
    build_split,
    episode_path,
    load_or_build_split,
    split_cache_folder,
    stats_path,
)
from vlln.tasks.splits import house_seeds
from vlln.world.catalogue import default_catalogue
from vlln.world.generator import HouseParameters, generate_house

SMALL = HouseParameters(min_rooms=3, max_rooms=4, min_area=35.0, max_area=55.0)
CONFIG = EpisodeGenConfig(starts_per_target=2, min_start_distance=1.5, max_start_distance=12.0)
SPLIT_CONFIG = EpisodeGenConfig(targets_per_house=6)
SEED = 7


class SmallHouses(SceneCache):
    """Small houses under the procedural scene ids, each built once, so builds stay fast."""

    def __init__(self) -> None:
        super().__init__()
        self.sims: dict[str, Simulator] = {}

    def get(self, scene_id: str) -> Simulator:
        if scene_id not in self.sims:
            self.sims[scene_id] = Simulator(generate_house(procedural_seed(scene_id), SMALL))
        return self.sims[scene_id]

    def close(self) -> None:
        for sim in self.sims.values():
            sim.close()


class RecordingWriter(InstructionWriter):
    """Keeps every full instruction it writes, by target id."""

    written: ClassVar[dict[int, FullInstruction]] = {}

    def full_instruction(self, target_id: int, rng: np.random.Generator) -> FullInstruction:
        made = super().full_instruction(target_id, rng)
        RecordingWriter.written[target_id] = made
        return made


@pytest.fixture(scope="module")
def sim() -> Any:
    with Simulator(generate_house(SEED, SMALL)) as simulator:
        yield simulator


@pytest.fixture(scope="module")
def made(sim: Simulator) -> HouseEpisodes:
    RecordingWriter.written = {}
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(generation, "InstructionWriter", RecordingWriter)
        return generate_house_episodes(sim, np.random.default_rng(0), CONFIG)


@pytest.fixture(scope="module")
def scenes() -> Any:
    cache = SmallHouses()
    yield cache
    cache.close()


def all_episodes(made: HouseEpisodes) -> list[Episode]:
    return [*made.iign, *made.ign, *made.objectnav]


def target_id(episode: Episode) -> int:
    return int(episode.instruction.instance_id[0])


# --- one house --------------------------------------------------------------------------


def test_the_three_lists_are_aligned_with_unique_ids(made: HouseEpisodes) -> None:
    assert len(made.iign) > 10
    assert len(made.iign) == len(made.ign) == len(made.objectnav) == made.stats.episodes
    for a, b, c in zip(made.iign, made.ign, made.objectnav, strict=True):
        assert a.episode_id == b.episode_id == c.episode_id
        assert a.start_position == b.start_position == c.start_position
        assert a.start_rotation == b.start_rotation == c.start_rotation
        assert target_id(a) == target_id(b) == target_id(c)
        seed_and_target, k = divmod(int(a.episode_id), 100)
        assert divmod(seed_and_target, 10_000) == (SEED, target_id(a)) and 0 <= k < 2
        assert a.episode_id.isdecimal()
    assert len({e.episode_id for e in made.iign}) == len(made.iign)
    assert {e.scene_id for e in all_episodes(made)} == {"vlln/house_00007/house_00007.glb"}
    assert all(e.instruction.instruction_text.endswith(".") for e in all_episodes(made))


def test_starts_are_navigable_and_within_the_geodesic_range(
    sim: Simulator, made: HouseEpisodes
) -> None:
    for episode in all_episodes(made):
        x, y, z = episode.start_position
        assert sim.grid.is_navigable(x, z) and y == sim.grid.floor_y
        goals = [(vp.position[0], vp.position[2]) for g in episode.goals for vp in g.view_points]
        distance = sim.geodesic_field(goals).distance(x, z)
        assert CONFIG.min_start_distance <= distance <= CONFIG.max_start_distance
        assert distance == pytest.approx(episode.info["geodesic_distance"], abs=1e-3)
        qx, qy, qz, qw = episode.start_rotation
        assert qx == qz == 0.0 and math.isclose(qy * qy + qw * qw, 1.0)


def test_a_target_has_distinct_starts(made: HouseEpisodes) -> None:
    starts: dict[int, list[tuple[float, ...]]] = {}
    for episode in made.iign:
        starts.setdefault(target_id(episode), []).append(episode.start_position)
    assert any(len(s) == 2 for s in starts.values())
    assert all(len(set(s)) == len(s) for s in starts.values())


def test_view_points_lie_on_navigable_cells_inside_the_grown_box(
    sim: Simulator, made: HouseEpisodes
) -> None:
    for episode in made.objectnav:
        for goal in episode.goals:
            lo, hi = np.array(goal.bbox[:3]) - 0.6, np.array(goal.bbox[3:]) + 0.6
            assert goal.radius is None
            assert goal.position == pytest.approx(tuple((lo + hi) / 2))
            for vp in goal.view_points:
                x, y, z = vp.position
                assert lo[0] <= x <= hi[0] and lo[2] <= z <= hi[2] and y == sim.grid.floor_y
                assert sim.grid.is_navigable(x, z)
        assert len(episode.goals[0].view_points) >= CONFIG.min_view_points


def test_ign_instructions_single_out_their_target(sim: Simulator, made: HouseEpisodes) -> None:
    for episode in made.ign:
        target = target_id(episode)
        written = RecordingWriter.written[target]
        assert matching_instances(sim.house, written.description) == [target]
        assert episode.instruction.instruction_text == written.text
        assert episode.instruction.instruction_info == tuple(written.instruction_info)
        assert episode.instruction.task_type == "ign"
        assert episode.instruction.instance_id == (str(target),)
        assert len(episode.goals) == 1


def test_iign_says_only_the_category(sim: Simulator, made: HouseEpisodes) -> None:
    for episode in made.iign:
        target = sim.house.instance(target_id(episode))
        assert episode.object_category == target.category
        assert episode.instruction.instruction_text == f"Search for the {target.category}."
        assert episode.instruction.instruction_info is None
        assert episode.instruction.task_type == "iign"
        assert episode.goals[0].bbox == (*target.box.min, *target.box.max)


def test_objectnav_goals_are_every_instance_of_the_category(
    sim: Simulator, made: HouseEpisodes
) -> None:
    for iign, episode in zip(made.iign, made.objectnav, strict=True):
        instances = sim.house.instances_of(episode.object_category)
        ids = [int(i) for i in episode.instruction.instance_id]
        assert sorted(ids) == sorted(i.id for i in instances)
        assert ids[0] == target_id(iign) and episode.goals[0] == iign.goals[0]
        for instance_id, goal in zip(ids, episode.goals, strict=True):
            box = sim.house.instance(instance_id).box
            assert goal.bbox == (*box.min, *box.max)
        assert episode.instruction.instruction_text == iign.instruction.instruction_text
    assert any(len(e.goals) > 1 for e in made.objectnav)


def test_statistics_account_for_every_instance(sim: Simulator, made: HouseEpisodes) -> None:
    stats = made.stats
    used = {target_id(e) for e in made.iign}
    assert stats.targets == len(sim.house.instances)
    assert stats.used == len(used)
    assert stats.targets - stats.used == sum(stats.skipped.values())
    assert set(stats.skipped) == set(SKIP_REASONS)
    expected: dict[int, int] = {}
    for target in used:
        others = len(sim.house.instances_of(sim.house.instance(target).category)) - 1
        expected[others] = expected.get(others, 0) + 1
    assert dict(stats.distractors) == expected
    assert sum(stats.episodes_per_category.values()) == len(made.iign)


def test_targets_no_instruction_singles_out_are_skipped(
    sim: Simulator, made: HouseEpisodes
) -> None:
    writer = InstructionWriter(sim.house)
    ambiguous = set()
    for instance in sim.house.instances:
        try:
            writer.full_instruction(instance.id, np.random.default_rng(0))
        except AmbiguousTargetError:
            ambiguous.add(instance.id)
    assert not ambiguous & {target_id(e) for e in made.iign}
    assert made.stats.skipped["ambiguous_instruction"] <= len(ambiguous)


def test_targets_per_house_caps_the_targets(sim: Simulator) -> None:
    config = EpisodeGenConfig(targets_per_house=3)
    made = generate_house_episodes(sim, np.random.default_rng(1), config)
    assert len({target_id(e) for e in made.iign}) == 3 == made.stats.used
    assert [target_id(e) for e in made.iign] == sorted(target_id(e) for e in made.iign)


def test_a_start_range_no_target_can_meet_skips_every_target(sim: Simulator) -> None:
    config = EpisodeGenConfig(min_start_distance=200.0, max_start_distance=300.0)
    made = generate_house_episodes(sim, np.random.default_rng(0), config)
    assert made.iign == [] and made.stats.skipped["no_start_in_range"] > 0


@pytest.mark.parametrize(
    "changes",
    [
        {"starts_per_target": 0},
        {"min_start_distance": 5.0, "max_start_distance": 2.0},
        {"max_start_distance": math.inf},
        {"view_point_stride": 0},
        {"targets_per_house": -1},
        {"starts_per_target": 50, "start_pool_size": 10},
    ],
)
def test_bad_settings_are_config_errors(changes: dict[str, Any]) -> None:
    with pytest.raises(ConfigError):
        EpisodeGenConfig(**changes)


def test_a_house_without_a_seed_is_refused(sim: Simulator) -> None:
    house = dataclasses.replace(sim.house, seed=None)
    with Simulator(house) as unseeded, pytest.raises(ConfigError, match="no seed"):
        generate_house_episodes(unseeded, np.random.default_rng(0))


# --- split files ------------------------------------------------------------------------


def read_all(folder: Path) -> dict[str, bytes]:
    return {path.name: path.read_bytes() for path in sorted(folder.iterdir())}


@pytest.mark.slow
def test_a_split_build_is_byte_identical_and_reads_back(
    tmp_path: Path, scenes: SmallHouses
) -> None:
    first = build_split("val", 2, tmp_path / "a", 0, SPLIT_CONFIG, scenes=scenes, progress=False)
    second = build_split("val", 2, tmp_path / "b", 0, SPLIT_CONFIG, scenes=scenes, progress=False)
    files = read_all(first)
    assert sorted(files) == [
        "val_ign.json.gz",
        "val_iign.json.gz",
        "val_objectnav.json.gz",
        "val_stats.json",
    ]
    assert files == read_all(second)
    for task in TaskType:
        expected: list[Episode] = []
        for seed in house_seeds("val", 2):
            house = generate_house_episodes(
                scenes.get(procedural_scene_id(seed)), house_rng(0, seed), SPLIT_CONFIG
            )
            expected += house.of_task(task)
        assert read_episodes(episode_path(first, "val", task)) == expected


def test_adding_houses_keeps_the_earlier_houses(tmp_path: Path, scenes: SmallHouses) -> None:
    one = build_split("val", 1, tmp_path / "one", 5, SPLIT_CONFIG, scenes=scenes, progress=False)
    two = build_split("val", 2, tmp_path / "two", 5, SPLIT_CONFIG, scenes=scenes, progress=False)
    shorter = read_episodes(episode_path(one, "val", "ign"))
    longer = read_episodes(episode_path(two, "val", "ign"))
    assert shorter and longer[: len(shorter)] == shorter and len(longer) > len(shorter)
    other_seed = build_split(
        "val", 1, tmp_path / "s", 6, SPLIT_CONFIG, scenes=scenes, progress=False
    )
    assert read_episodes(episode_path(other_seed, "val", "ign")) != shorter


def test_the_stats_file_sums_the_houses(tmp_path: Path, scenes: SmallHouses) -> None:
    out = build_split("val", 2, tmp_path, 0, SPLIT_CONFIG, scenes=scenes, progress=False)
    stats = json.loads(stats_path(out, "val").read_text())
    episodes = read_episodes(episode_path(out, "val", "iign"))
    assert (
        stats["totals"]["episodes"] == len(episodes) == sum(h["episodes"] for h in stats["houses"])
    )
    assert stats["totals"]["houses"] == 2
    assert [h["house_seed"] for h in stats["houses"]] == house_seeds("val", 2)
    assert stats["build"]["house_seeds"] == house_seeds("val", 2)


def test_load_or_build_builds_once(
    tmp_path: Path, scenes: SmallHouses, monkeypatch: pytest.MonkeyPatch
) -> None:
    built = load_or_build_split(
        "test", "iign", 1, tmp_path, 0, SPLIT_CONFIG, scenes=scenes, progress=False
    )
    folder = split_cache_folder(tmp_path, "small", 1)
    assert built == read_episodes(episode_path(folder, "test", TaskType.IIGN))
    assert {e.scene_id for e in built} == {"vlln/house_00076/house_00076.glb"}
    two = load_or_build_split("test", "iign", 2, tmp_path, 0, SPLIT_CONFIG, scenes=scenes)
    assert len({e.scene_id for e in two}) == 2

    def refuse(*args: Any, **kwargs: Any) -> Path:
        raise AssertionError("the cached split was built again")

    monkeypatch.setattr(split_files, "build_split", refuse)
    # Each number of houses keeps its own files: building two left the one-house split.
    assert load_or_build_split("test", "ign", 1, tmp_path, 0, SPLIT_CONFIG, scenes=scenes) != []
    assert load_or_build_split("test", "iign", 2, tmp_path, 0, SPLIT_CONFIG, scenes=scenes) == two
    with pytest.raises(AssertionError, match="built again"):
        load_or_build_split("test", "ign", 3, tmp_path, 0, SPLIT_CONFIG, scenes=scenes)


def test_a_split_built_from_another_catalogue_is_built_again(
    tmp_path: Path, scenes: SmallHouses, monkeypatch: pytest.MonkeyPatch
) -> None:
    load_or_build_split("test", "ign", 1, tmp_path, 0, SPLIT_CONFIG, scenes=scenes, progress=False)
    stats = stats_path(split_cache_folder(tmp_path, "small", 1), "test")
    recorded = json.loads(stats.read_text())
    assert recorded["build"]["catalogue"] == default_catalogue().fingerprint()
    recorded["build"]["catalogue"] = "an older catalogue"
    stats.write_text(json.dumps(recorded))

    def refuse(*args: Any, **kwargs: Any) -> Path:
        raise AssertionError("the cached split was built again")

    monkeypatch.setattr(split_files, "build_split", refuse)
    with pytest.raises(AssertionError, match="built again"):
        load_or_build_split("test", "ign", 1, tmp_path, 0, SPLIT_CONFIG, scenes=scenes)
