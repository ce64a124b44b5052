"""`vlln bench data`: how many trajectories per hour one core collects, filters and writes.

The workload is the pipeline's trajectory stage on the first ``houses`` small training houses,
``per_house`` episodes each, in one process (so the rate is per core). Scene summaries, episode
files, the houses' simulators and the oracle's question classifier (read once per process, so
a real build pays it once for all its houses) are made before the clock starts; the timed part
is collection (which keeps the level views it renders), filtering, rendering the look-down
view of every kept frame and encoding both.
``mb_per_trajectory`` is the disk the kept trajectories' folders take (as ``du`` counts it),
per kept trajectory. ``cpu_seconds_per_kept_trajectory`` is the process's CPU time (every
thread, the rasteriser's included) per kept trajectory: unlike the hourly rates, it barely
moves with what else the machine runs, and ``kept_trajectories_per_cpu_hour`` is its inverse.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import DataBench
from vlln.datagen.build import (
    BuildConfig,
    build_house,
    choose_episodes,
    prepare_episodes,
    summarize,
)
from vlln.oracle.classifier.model import packaged_classifier
from vlln.tasks.scenes import SceneCache
from vlln.tasks.splits import house_seeds


def run_data_benchmark(settings: DataBench) -> list[Figure]:
    """Build the fixed workload once in a temporary folder and print its figures."""
    as_json = settings.as_json
    config = BuildConfig(houses=settings.houses, per_house=settings.per_house, preset="small")
    figures: list[Figure] = []

    def note(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, as_json)

    seeds = house_seeds(config.split, config.houses)
    scenes = SceneCache(capacity=len(seeds))
    with tempfile.TemporaryDirectory(prefix="vlln-bench-data-") as out:
        root = Path(out)
        try:
            by_house = prepare_episodes(root, config, seeds, scenes, progress=False)
            work = []
            for seed in seeds:
                scene_id = config.scene_id(seed)
                work.append(
                    (scenes.get(scene_id), choose_episodes(by_house[scene_id], config, seed))
                )
            packaged_classifier()
            started, cpu_started = time.perf_counter(), time.process_time()
            for sim, episodes in work:
                build_house(root, sim, episodes, config, progress=False)
            seconds = time.perf_counter() - started
            cpu_seconds = time.process_time() - cpu_started
        finally:
            scenes.close()
        summary = summarize(root)
    attempted, kept, frames = summary.attempted, summary.kept, summary.frames
    note("trajectories_attempted", attempted, "count")
    note("trajectories_per_hour", 3600.0 * attempted / seconds, "trajectories/h/core")
    note("kept_trajectories_per_hour", 3600.0 * kept / seconds, "trajectories/h/core")
    note("seconds_per_trajectory", seconds / attempted, "s")
    note("yield", 100.0 * kept / attempted, "%")
    note("frames_written_per_second", frames / seconds, "frames/s")
    note("mb_per_trajectory", summary.mb_per_trajectory, "MB")
    note("frames_per_trajectory", frames / kept if kept else 0.0, "frames")
    note("cpu_seconds_per_kept_trajectory", cpu_seconds / kept if kept else 0.0, "s")
    note("kept_trajectories_per_cpu_hour", 3600.0 * kept / cpu_seconds, "trajectories/h")
    return figures
