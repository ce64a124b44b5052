"""``vlln data build``: every stage of the pipeline for the first N houses of a split, with a
builder that makes the houses' trajectories (an executor, :mod:`vlln.eval.executor`, the
protocol ``vlln eval`` shares): :class:`LocalBuilder` in this process, or
:class:`vlln.cluster.data.RayBuilder` on a cluster. The runner (:func:`build_dataset`) alone
owns the rest, so both write the same dataset: the settings, the sharding, the house locks,
stages 1-2, which houses are left to build, and progress.

::

    <out>/build.json                      the settings (a rerun must use the same ones)
    <out>/scene_summary/<house>/          stage 1: object_dict.json, region_dict.json
    <out>/episodes/<split>_*.json.gz      stage 2: IIGN, IGN, ObjectNav episodes and stats
    <out>/trajectories/<house>/           stages 3-5: collected, filtered, written trajectories

(names: :mod:`vlln.datagen.layout`). ``preset`` picks the houses, the benchmark's (``mp3d``,
what ``vlln eval`` scores on) unless told, and is always recorded (a ``build.json`` without it
was built on ``small`` houses, before the setting existed). ``floors`` picks small houses of
1, 2 or 3 storeys joined by stairs (the scene ids of houses with several storeys end in
``_2f``/``_3f``). ``task`` picks
the episodes walked (IIGN with dialog; IGN and ObjectNav without, see
:mod:`vlln.datagen.collector.collect`) and ``policy`` how (frontier exploration, or the
shortest path). A setting at its first value (one storey, IIGN, frontier) is not recorded, so
the ``build.json`` of such a build is what it was before the setting existed, and a folder
built then resumes.

Houses are the unit of sharding (``--shard i/n`` takes every n-th house), of locking (a build
holds its houses, :mod:`.house_locks`, so two builds never write one house) and of completion
(a finished house has ``meta/info.json``); within a house the journal makes a killed build resume
at the next untried episode. Each trajectory draws its randomness from (seed, episode id) only,
so a resumed, sharded, distributed or uninterrupted build writes the same dataset.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal, Self

import numpy as np
from pydantic import Field, field_validator, model_validator
from tqdm import tqdm

from vlln import __version__
from vlln.datagen.collector.collect import CollectorConfig, collect_trajectory
from vlln.datagen.filtering import FilterConfig, rejection_reason
from vlln.datagen.goals import FollowerWalks
from vlln.datagen.house_locks import lock_houses
from vlln.datagen.layout import (
    EPISODES_DIR,
    FORMAT_VERSION,
    LAST_FILES,
    SCENE_SUMMARY_DIR,
    SETTINGS_CAP,
    SETTINGS_FILE,
    TRAJECTORIES_DIR,
    house_dir,
    house_dir_name,
    is_finished,
)
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.datagen.views import LevelViews, down_views, final_down_view
from vlln.datagen.writer import HouseWriter
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.executor import Executor
from vlln.eval.play import episode_seed
from vlln.eval.sharding import Shard
from vlln.files import (
    parse_json,
    refuse_other_settings,
    write_bytes_atomic,
    write_text_atomic,
)
from vlln.oracle.settings import OracleSettings
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.generation import EpisodeGenConfig, episode_config
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import TaskType
from vlln.tasks.split_files import build_split, episode_path
from vlln.tasks.splits import house_seeds
from vlln.world.catalogue import default_catalogue
from vlln.world.generator.presets import SMALL
from vlln.world.options import PresetOptions
from vlln.world.scene_summary import export_scene_summary

FLOOR_CHOICES = (1, 2, 3)  # storeys a procedural house can have


class BuildOptions(PresetOptions):
    """The settings of a build that ``vlln data build`` takes as flags."""

    houses: Annotated[int, Field(ge=1)]
    """houses of the split to use"""
    split: str = "train"
    """house split"""
    seed: Annotated[int, Field(ge=0)] = 0
    """seed of every random choice"""
    per_house: Annotated[int, Field(ge=0)] = 20
    """trajectories tried per house (0: every episode of the task)"""
    floors: int = 1
    """storeys of every small house, joined by stairs, 1 to 3 (mp3d houses draw theirs)"""
    task: Literal["iign", "ign", "objectnav"] = "iign"
    """episodes to walk: iign (with dialog), ign or objectnav (no dialog, as in the paper)"""
    policy: Literal["frontier", "shortest"] = "frontier"
    """frontier exploration until the target is seen, or the shortest path to it"""

    @field_validator("floors")
    @classmethod
    def _known_floors(cls, value: int) -> int:
        if value not in FLOOR_CHOICES:
            raise ValueError(f"must be one of {', '.join(map(str, FLOOR_CHOICES))}, got {value}")
        return value

    @model_validator(mode="after")
    def _floors_of_small_houses(self) -> Self:
        if self.floors != 1 and self.preset != SMALL.name:
            raise ValueError(
                f"--floors sets the storeys of small houses; {self.preset} houses draw theirs "
                "from the seed: add --preset small, or drop --floors"
            )
        return self


class BuildConfig(BuildOptions):
    """What a build makes; recorded in ``build.json`` and in every house's info."""

    # At their first values (one storey, IIGN, frontier), as before they existed.
    unrecorded_at_default = ("floors", "task", "policy")

    episodes: EpisodeGenConfig = Field(default_factory=EpisodeGenConfig)
    """episode settings (none given: those of the preset's splits, as eval builds them)"""
    collector: CollectorConfig = Field(default_factory=CollectorConfig)
    filter: FilterConfig = Field(default_factory=FilterConfig)

    @model_validator(mode="before")
    @classmethod
    def _preset_episodes(cls, values: Any) -> Any:
        """Episodes drawn as the preset's evaluation splits draw them, unless given."""
        if isinstance(values, dict) and values.get("episodes") is None:
            preset = values.get("preset", PresetOptions.model_fields["preset"].default)
            return {**values, "episodes": episode_config(str(preset))}
        return values

    def scene_id(self, seed: int) -> str:
        """The scene id of the split's house ``seed`` with this build's preset and storeys."""
        return procedural_scene_id(seed, self.floors, self.preset)

    def settings(self) -> dict[str, Any]:
        """What ``build.json`` and each house's info record: the settings and what else
        decides the data (the oracle, the code's and trajectory format's versions, the
        catalogue)."""
        return {
            **self.to_json(),
            "oracle": "rules",
            "vlln_version": __version__,
            "trajectory_format": FORMAT_VERSION,
            "catalogue": default_catalogue().fingerprint(),
        }


@dataclass(frozen=True)
class HouseWork:
    """One house to build: its split seed and the episodes to attempt in it."""

    seed: int
    episodes: list[Episode]


@dataclass(frozen=True)
class BuildJob:
    """What every house of a build shares: the dataset folder, the settings, and the
    simulators stages 1-2 used."""

    root: Path
    config: BuildConfig
    scenes: SceneCache


@dataclass(frozen=True)
class BuiltHouse:
    """A house's trajectories (stages 3-5), complete: ``files`` ({path under the dataset:
    bytes}) for the runner to write, or none when they were written in place."""

    seed: int
    files: dict[str, bytes] = field(default_factory=dict)


HouseBuilder = Executor[BuildJob, HouseWork, BuiltHouse]
"""An executor of houses' trajectories (:mod:`vlln.eval.executor`, the protocol ``vlln eval``
shares)."""


@dataclass
class LocalBuilder:
    """A :data:`HouseBuilder` that builds one house after the other in this process, into the
    dataset itself (a killed build resumes inside a house); ``progress`` shows a bar per
    house."""

    progress: bool = True
    label: str = ""

    def check(self, job: BuildJob) -> None:
        return None

    def play(
        self, job: BuildJob, items: list[HouseWork], commit: Callable[[list[BuiltHouse]], None]
    ) -> None:
        for house in items:
            sim = job.scenes.get(job.config.scene_id(house.seed))
            build_house(job.root, sim, house.episodes, job.config, self.progress)
            commit([BuiltHouse(house.seed)])


def write_house_files(root: Path, files: dict[str, bytes]) -> None:
    """Write a house's files into the dataset, the journal and ``meta/info.json`` last, so
    the house counts as finished only when all of it is on disk."""
    last = [name for name in files if _in_house(name) in LAST_FILES]
    for name in [n for n in files if n not in last] + sorted(last, key=_last_order):
        write_bytes_atomic(root / name, files[name])


def _in_house(name: str) -> str:
    """``trajectories/<house>/meta/info.json`` -> ``meta/info.json``."""
    return name.split("/", 2)[-1]


def _last_order(name: str) -> int:
    return LAST_FILES.index(_in_house(name))


def build_dataset(
    out: str | Path,
    config: BuildConfig,
    shard: Shard | None = None,
    progress: bool = True,
    builder: HouseBuilder | None = None,
) -> Path:
    """Run (or resume) every stage into ``out`` with ``builder`` (by default in this
    process); returns ``out``."""
    root = Path(out)
    builder = builder if builder is not None else LocalBuilder(progress)
    # Two simulators, SceneCache's default: a build or shard of two houses makes each once,
    # not once per stage (summaries, episodes, trajectories).
    cache = SceneCache(capacity=2)
    try:
        job = BuildJob(root, config, cache)
        builder.check(job)
        check_settings(root, config)
        mine = (shard or Shard(0, 1)).take(house_seeds(config.split, config.houses))
        with lock_houses(root, mine, config.scene_id):
            by_house = prepare_episodes(root, config, mine, cache, progress)
            todo = [
                HouseWork(
                    seed, choose_episodes(by_house.get(config.scene_id(seed), []), config, seed)
                )
                for seed in mine
                if not is_finished(house_dir(root, config.scene_id(seed)))
            ]
            where = f" {builder.label}" if builder.label else ""
            with tqdm(
                total=len(mine),
                initial=len(mine) - len(todo),
                desc=f"trajectories{where}",
                unit="house",
                disable=not progress,
            ) as bar:

                def commit(built: list[BuiltHouse]) -> None:
                    for house in built:
                        write_house_files(root, house.files)
                        bar.update(1)

                builder.play(job, todo, commit)
    finally:
        cache.close()
    return root


def prepare_episodes(
    root: Path, config: BuildConfig, seeds: list[int], cache: SceneCache, progress: bool
) -> dict[str, list[Episode]]:
    """Stages 1 and 2: scene summaries of ``seeds``, the split's episode files (built once;
    every shard builds the same bytes), and the episodes of the build's task by scene."""
    for seed in tqdm(seeds, desc="scene summaries", unit="house", disable=not progress):
        export_scene_summary(cache.get(config.scene_id(seed)).house, root / SCENE_SUMMARY_DIR)
    episodes_dir = root / EPISODES_DIR
    path = episode_path(episodes_dir, config.split, TaskType(config.task))
    if not path.exists():
        build_split(
            config.split,
            config.houses,
            episodes_dir,
            config.seed,
            config.episodes,
            scenes=cache,
            progress=progress,
            floors=config.floors,
            preset=config.preset,
        )
    return _episodes_by_scene(read_episodes(path))


def choose_episodes(episodes: list[Episode], config: BuildConfig, seed: int) -> list[Episode]:
    """The house's episodes to attempt, drawn without replacement, in a fixed order (the
    same draw for every task: their episode lists are aligned one to one)."""
    if config.per_house == 0 or config.per_house >= len(episodes):
        return list(episodes)
    rng = np.random.default_rng(np.random.SeedSequence([config.seed, seed, 5]))
    picked = rng.choice(len(episodes), config.per_house, replace=False)
    return [episodes[int(i)] for i in sorted(picked)]


def build_house(
    root: Path, sim: Simulator, episodes: list[Episode], config: BuildConfig, progress: bool
) -> None:
    """Stages 3-5 for one house: collect, filter and write each episode not yet tried."""
    if not episodes:
        return
    writer = HouseWriter(root / TRAJECTORIES_DIR, episodes[0].scene_id, sim.config.camera)
    if writer.finished:
        return
    todo = [e for e in episodes if e.episode_id not in writer.attempts]
    bar = tqdm(
        todo,
        desc=house_dir_name(episodes[0].scene_id),
        unit="traj",
        disable=not progress,
        leave=False,
    )
    for episode in bar:
        # vlln eval's default oracle, seeded as eval seeds an episode's: the answers are the
        # ones a model asking the same questions in the same places hears.
        oracle = OracleSettings().make(episode_seed(config.seed, "oracle", episode))
        level = LevelViews()
        trajectory = collect_trajectory(
            sim,
            episode,
            oracle,
            config.seed,
            config.collector,
            config.policy == "shortest",
            on_frame=level.keep,
        )
        final_down = final_down_view(sim, trajectory)
        reason = rejection_reason(trajectory, (level.last, final_down), config.filter)
        if reason is None:
            down = down_views(sim, trajectory, final_down)
            writer.write_kept(trajectory, level.stored, down, FollowerWalks(sim, trajectory))
        else:
            writer.write_rejected(episode.episode_id, reason)
    writer.finish({"generator": config.settings()})


@dataclass(frozen=True)
class BuildSummary:
    """What the finished houses of a dataset hold, and the disk their trajectories take."""

    attempted: int
    kept: int
    frames: int
    disk_bytes: int  # allocated on disk under trajectories/, as `du` counts it

    @property
    def mb_per_trajectory(self) -> float:
        return self.disk_bytes / 1e6 / self.kept if self.kept else 0.0

    def line(self) -> str:
        none_kept = self.attempted and not self.kept
        return (
            f"kept {self.kept} of {self.attempted} trajectories ({self.frames} frames); "
            f"{self.disk_bytes / 1e6:.1f} MB on disk, {self.mb_per_trajectory:.2f} MB per "
            "kept trajectory" + ("; none kept: `vlln data stats` shows why" if none_kept else "")
        )


def summarize(root: str | Path) -> BuildSummary:
    """Totals over the finished house folders of ``root`` (those with meta/info.json)."""
    attempted = kept = frames = disk = 0
    for folder in house_folders(root):
        if not is_finished(folder):
            continue
        info = HouseDataset(folder).info
        attempted += int(info["attempted"])
        kept += int(info["total_episodes"])
        frames += int(info["total_frames"])
        disk += sum(p.stat().st_blocks * 512 for p in folder.rglob("*") if p.is_file())
    return BuildSummary(attempted, kept, frames, disk)


def _episodes_by_scene(episodes: list[Episode]) -> dict[str, list[Episode]]:
    grouped: dict[str, list[Episode]] = {}
    for episode in episodes:
        grouped.setdefault(episode.scene_id, []).append(episode)
    return grouped


@dataclass(frozen=True)
class Strategy:
    """Which houses a dataset was built on, the task it walked and how."""

    preset: str
    task: str
    policy: str


def recorded_strategy(root: Path) -> Strategy | None:
    """The strategy of the dataset at ``root``, from its ``build.json`` (a setting left out is
    at its default, the preset at ``small``); None for a folder without one."""
    path = root / SETTINGS_FILE
    if not path.exists():
        return None
    try:
        recorded = _with_legacy_preset(parse_json(SETTINGS_CAP.read(path)))
        task, policy = (
            str(recorded.get(name, BuildOptions.model_fields[name].default))
            for name in ("task", "policy")
        )
    except (ValueError, AttributeError) as error:
        raise DataFormatError(f"{path} is not a JSON object of settings ({error})") from None
    return Strategy(str(recorded["preset"]), task, policy)


def _with_legacy_preset(recorded: Any) -> Any:
    """Settings of a ``build.json``; one written before the preset was recorded was built on
    small houses."""
    if isinstance(recorded, dict) and "preset" not in recorded:
        return {**recorded, "preset": SMALL.name}
    return recorded


def check_settings(root: Path, config: BuildConfig) -> None:
    """Record the settings on the first run; refuse to mix settings in one folder."""
    path = root / SETTINGS_FILE
    wanted = config.settings()
    if path.exists():
        data = SETTINGS_CAP.read(path)
        try:
            recorded = _with_legacy_preset(parse_json(data))
        except DataFormatError as error:
            raise ConfigError(f"{path}: {error}; delete it to rebuild") from None
        if not isinstance(recorded, dict):
            raise ConfigError(f"{path} is not a JSON object of settings; delete it to rebuild")
        refuse_other_settings(root, recorded, wanted, "a dataset")
        return
    root.mkdir(parents=True, exist_ok=True)
    write_text_atomic(path, json.dumps(wanted, indent=2) + "\n")
