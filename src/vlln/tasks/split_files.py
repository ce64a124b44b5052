"""Split files: the episodes of a split's procedural houses, written once and read back.

``build_split`` writes ``<split>_<task>.json.gz`` for the three tasks and ``<split>_stats.json``
(per-house statistics, totals, and the build settings); ``load_or_build_split`` reads a cached
split and rebuilds it when its recorded settings differ from the ones asked for.
"""

from __future__ import annotations

import json
import os
from dataclasses import asdict
from functools import lru_cache
from pathlib import Path
from typing import Any

from tqdm import tqdm

from vlln import __version__
from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, write_text_atomic
from vlln.tasks.episode import Episode, read_episodes, reference_convention_problems, write_episodes
from vlln.tasks.generation import (
    EpisodeGenConfig,
    HouseStats,
    check_count,
    episode_config,
    generate_house_episodes,
    house_rng,
)
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import TaskType
from vlln.tasks.splits import house_seeds
from vlln.world.catalogue import default_catalogue
from vlln.world.generator.presets import SMALL

# The stats file holds a few hundred bytes per house; an unreadable one rebuilds the split.
STATS_CAP = ReadCap("a split's stats file", 16)


def episode_path(out_dir: str | Path, split: str, task: TaskType | str) -> Path:
    """``<out_dir>/<split>_<task>.json.gz``."""
    return Path(out_dir) / f"{split}_{TaskType.parse(str(task)).value}.json.gz"


def stats_path(out_dir: str | Path, split: str) -> Path:
    """``<out_dir>/<split>_stats.json``: per-house statistics, totals and the build settings."""
    return Path(out_dir) / f"{split}_stats.json"


def build_split(
    split: str,
    houses: int,
    out_dir: str | Path,
    rng_seed: int = 0,
    config: EpisodeGenConfig | None = None,
    *,
    scenes: SceneCache | None = None,
    progress: bool = True,
    floors: int = 1,
    preset: str = SMALL.name,
) -> Path:
    """Write the episodes of the first ``houses`` houses of ``split`` to ``out_dir``
    (houses of ``preset``; ``small`` houses of ``floors`` storeys: a target is often on
    another storey than the start).

    Writes ``<split>_iign.json.gz``, ``<split>_ign.json.gz``, ``<split>_objectnav.json.gz``
    and, last, ``<split>_stats.json``; the same arguments give byte-identical files. Houses
    come from ``scenes`` (which the caller closes) or from a cache made and closed here.
    Returns ``out_dir``.
    """
    config = config or episode_config(preset)
    check_count("rng_seed", rng_seed, 0)
    seeds = house_seeds(split, houses)
    cache = scenes if scenes is not None else SceneCache(capacity=1)
    episodes: dict[TaskType, list[Episode]] = {task: [] for task in TaskType}
    per_house: list[HouseStats] = []
    try:
        for seed in tqdm(seeds, desc=f"{split} episodes", unit="house", disable=not progress):
            sim = cache.get(procedural_scene_id(seed, floors, preset))
            made = generate_house_episodes(sim, house_rng(rng_seed, seed), config)
            for task in TaskType:
                episodes[task].extend(made.of_task(task))
            per_house.append(made.stats)
    finally:
        if scenes is None:
            cache.close()
    out = Path(out_dir)
    for task in TaskType:
        problems = reference_convention_problems(episodes[task])
        if problems:
            raise DataFormatError(f"{split} {task.value} episodes: {problems[0]}")
        write_episodes(episode_path(out, split, task), episodes[task])
    totals = HouseStats(-1, "", 0)
    for stats in per_house:
        totals.add(stats)
    document = {
        "build": _build_settings(split, seeds, rng_seed, config, floors, preset),
        "totals": {"houses": len(per_house), **totals.counts_json()},
        "houses": [stats.to_json() for stats in per_house],
    }
    write_text_atomic(stats_path(out, split), json.dumps(document, indent=2) + "\n")
    return out


def load_or_build_split(
    split: str,
    task: TaskType | str,
    houses: int,
    cache_dir: str | Path,
    rng_seed: int = 0,
    config: EpisodeGenConfig | None = None,
    *,
    scenes: SceneCache | None = None,
    progress: bool = True,
    preset: str = SMALL.name,
) -> list[Episode]:
    """The split's episodes of ``task`` on houses of ``preset``: read from ``cache_dir``
    (a folder per preset and number of houses, so a run on another ``houses`` leaves the
    others' files in place), built there first if needed.

    The cache is rebuilt when its stats file records another seed, settings or vlln version
    than asked for.
    """
    config = config or episode_config(preset)
    folder = split_cache_folder(cache_dir, preset, houses)
    path = episode_path(folder, split, task)
    wanted = _build_settings(split, house_seeds(split, houses), rng_seed, config, 1, preset)
    if not (path.exists() and _recorded_settings(stats_path(folder, split)) == wanted):
        build_split(
            split,
            houses,
            folder,
            rng_seed,
            config,
            scenes=scenes,
            progress=progress,
            preset=preset,
        )
    stat = path.stat()
    return list(_read_split(str(path), stat.st_mtime_ns, stat.st_size))


def default_cache_dir() -> Path:
    """Where built splits are kept: ``$XDG_CACHE_HOME/vlln/episodes`` (~/.cache by default)."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "vlln" / "episodes"


def split_cache_folder(cache_dir: str | Path, preset: str, houses: int) -> Path:
    """Where :func:`load_or_build_split` keeps the split files of ``houses`` houses."""
    return Path(cache_dir) / preset / f"{houses}_houses"


@lru_cache(maxsize=3)
def _read_split(path: str, mtime_ns: int, size: int) -> tuple[Episode, ...]:
    """A split file's episodes, parsed once per process while the file is unchanged: runs that
    share a split (`vlln bench fidelity` plays six, on three tasks' files) would otherwise
    parse thousands of episodes each. Episodes are frozen, so callers can share them."""
    return tuple(read_episodes(path))


def _build_settings(
    split: str,
    seeds: list[int],
    rng_seed: int,
    config: EpisodeGenConfig,
    floors: int = 1,
    preset: str = SMALL.name,
) -> dict[str, Any]:
    settings = {
        "split": split,
        "house_seeds": seeds,
        "rng_seed": rng_seed,
        "config": asdict(config),
        "vlln_version": __version__,
        "catalogue": default_catalogue().fingerprint(),
    }
    if floors != 1:  # one-storey settings stay as they were
        settings["floors"] = floors
    if preset != SMALL.name:
        settings["preset"] = preset
    return settings


def _recorded_settings(path: Path) -> Any:
    try:
        return parse_json(STATS_CAP.read(path)).get("build")
    except (OSError, ValueError, AttributeError):
        return None
