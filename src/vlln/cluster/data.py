"""``vlln data build --ray``: the data build's house builder for a Ray cluster.

The build runner (:func:`vlln.datagen.build.build_dataset`) writes the settings, builds
stages 1-2 and picks the unfinished houses exactly as for a local build; this builder sends
each house's trajectories (stages 3-5) to the cluster as one Ray task. A worker builds the
house into a temporary folder of its own and returns the files; the driver writes them into
the dataset, the house's journal and then ``meta/info.json`` last, so a house counts as
finished only when all of it is on disk, and a rerun resumes at the unfinished houses. The
dataset equals a local build: every file of a house depends only on (settings, house, its
episodes).
"""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES, collect_in_order, connect, remote_function
from vlln.datagen.build import (
    BuildConfig,
    BuildJob,
    BuiltHouse,
    HouseWork,
    build_dataset,
    build_house,
)
from vlln.datagen.layout import TRAJECTORIES_DIR
from vlln.tasks.episode import Episode
from vlln.tasks.scenes import SceneCache


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
            for path in sorted((root / TRAJECTORIES_DIR).rglob("*"))
            if path.is_file()
        }


@dataclass
class RayBuilder:
    """A :data:`~vlln.datagen.build.HouseBuilder` that builds on a Ray cluster (module doc):
    ``address`` as for :func:`vlln.cluster.scheduler.connect`, each house's task retried
    ``max_retries`` times when its worker dies."""

    address: str | None = None
    max_retries: int = DEFAULT_MAX_RETRIES
    label: str = "on Ray"

    def check(self, job: BuildJob) -> None:
        connect(self.address)  # an unreachable cluster fails before any work

    def play(
        self, job: BuildJob, items: list[HouseWork], commit: Callable[[list[BuiltHouse]], None]
    ) -> None:
        ray = connect(self.address)
        task = remote_function(build_house_files, self.max_retries)
        config_ref = ray.put(job.config)
        refs = [task.remote(config_ref, house.seed, house.episodes) for house in items]
        collect_in_order(refs, lambda index, files: commit([BuiltHouse(items[index].seed, files)]))


def build_dataset_ray(
    out: str | Path,
    config: BuildConfig,
    *,
    address: str | None = None,
    max_retries: int = DEFAULT_MAX_RETRIES,
    progress: bool = True,
) -> Path:
    """Build (or resume) the dataset into ``out`` on a Ray cluster with the build runner."""
    return build_dataset(out, config, progress=progress, builder=RayBuilder(address, max_retries))
