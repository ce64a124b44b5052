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
from vlln.datagen.build import BuildConfig, HouseWork, build_dataset, build_house
from vlln.datagen.layout import LAST_FILES, TRAJECTORIES_DIR
from vlln.files import write_bytes_atomic
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


def write_house_files(root: Path, files: dict[str, bytes]) -> None:
    """Write a house's files into the dataset, the journal and ``meta/info.json`` last."""
    last = [name for name in files if _in_house(name) in LAST_FILES]
    for name in [n for n in files if n not in last] + sorted(last, key=_last_order):
        write_bytes_atomic(root / name, files[name])


@dataclass
class RayBuilder:
    """Builds houses on a Ray cluster (module doc): ``address`` as for
    :func:`vlln.cluster.scheduler.connect`, each house's task retried ``max_retries`` times
    when its worker dies."""

    address: str | None = None
    max_retries: int = DEFAULT_MAX_RETRIES
    label: str = "on Ray"

    def check(self) -> None:
        connect(self.address)  # an unreachable cluster fails before any work

    def build(
        self,
        root: Path,
        config: BuildConfig,
        houses: list[HouseWork],
        scenes: SceneCache,
        finished: Callable[[], None],
    ) -> None:
        ray = connect(self.address)
        task = remote_function(build_house_files, self.max_retries)
        config_ref = ray.put(config)
        refs = [task.remote(config_ref, house.seed, house.episodes) for house in houses]

        def commit(_: int, files: dict[str, bytes]) -> None:
            write_house_files(root, files)
            finished()

        collect_in_order(refs, commit)


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


def _in_house(name: str) -> str:
    """``trajectories/<house>/meta/info.json`` -> ``meta/info.json``."""
    return name.split("/", 2)[-1]


def _last_order(name: str) -> int:
    return LAST_FILES.index(_in_house(name))
