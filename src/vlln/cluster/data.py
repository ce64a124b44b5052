"""``vlln data build --ray``: each house's trajectories (stages 3-5) as a Ray task.

The driver writes the settings, builds stages 1-2 (scene summaries and the split's episode
files: cheap next to the trajectories, and needed to choose each house's episodes), then sends
every unfinished house to the cluster. A worker builds the house into a temporary folder of
its own and returns the files; the driver writes them into the dataset, the house's journal
and then ``meta/info.json`` last, so a house counts as finished only when all of it is on disk,
and a rerun resumes at the unfinished houses. The dataset equals a local build: every file
of a house depends only on (settings, house, its episodes).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from tqdm import tqdm

from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES, collect_in_order, connect, remote_function
from vlln.datagen.build import (
    BuildConfig,
    build_house,
    check_settings,
    choose_episodes,
    prepare_episodes,
)
from vlln.datagen.house_locks import lock_houses
from vlln.datagen.layout import house_dir_name
from vlln.files import write_bytes_atomic
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache
from vlln.tasks.splits import house_seeds

_LAST = ("meta/journal.jsonl", "meta/info.json")  # written after every other file, in order


def build_house_files(config: BuildConfig, seed: int, episodes: list[Episode]) -> dict[str, bytes]:
    """The Ray task: one house's trajectory folder, as {path under the dataset: bytes}."""
    cache = SceneCache(capacity=1)
    with tempfile.TemporaryDirectory(prefix="vlln-house-") as temp:
        root = Path(temp)
        try:
            build_house(root, cache.get(config.scene_id(seed)), episodes, config, False)
        finally:
            cache.close()
        return {
            path.relative_to(root).as_posix(): path.read_bytes()
            for path in sorted((root / "trajectories").rglob("*"))
            if path.is_file()
        }


def build_dataset_ray(
    out: str | Path,
    config: BuildConfig,
    *,
    address: str | None = None,
    max_retries: int = DEFAULT_MAX_RETRIES,
    progress: bool = True,
) -> Path:
    """Build (or resume) the dataset into ``out`` on a Ray cluster (module doc)."""
    root = Path(out)
    ray = connect(address)  # an unreachable cluster fails before any work
    check_settings(root, config)
    seeds = house_seeds(config.split, config.houses)
    with lock_houses(root, seeds, config.scene_id):  # as a local build does
        cache = SceneCache(capacity=1)
        try:
            by_house = prepare_episodes(root, config, seeds, cache, progress)
        finally:
            cache.close()
        todo = [seed for seed in seeds if not _finished(root, config.scene_id(seed))]
        task = remote_function(build_house_files, max_retries)
        config_ref = ray.put(config)
        refs = []
        for seed in todo:
            episodes = by_house.get(config.scene_id(seed), [])
            refs.append(task.remote(config_ref, seed, choose_episodes(episodes, config, seed)))
        with tqdm(total=len(todo), desc="houses on Ray", unit="house", disable=not progress) as bar:

            def commit(_: int, files: dict[str, bytes]) -> None:
                last = [name for name in files if name.split("/", 2)[-1] in _LAST]
                for name in [n for n in files if n not in last] + sorted(last, key=_last_order):
                    write_bytes_atomic(root / name, files[name])
                bar.update(1)

            collect_in_order(refs, commit)
    return root


def _last_order(name: str) -> int:
    return _LAST.index(name.split("/", 2)[-1])


def _finished(root: Path, scene_id: str) -> bool:
    folder = root / "trajectories" / house_dir_name(scene_id)
    return (folder / "meta" / "info.json").exists()
