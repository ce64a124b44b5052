"""`vlln bench eval`: how many episodes per hour the evaluation runner plays on this machine.

The workload is the benchmark's headline setting: the frontier agent on IIGN with a dialog
budget of 5 (the rule oracle answering), over a fixed set of test episodes (the first
``episodes`` of the test split's first house). The split is built or read from the cache and
the house's simulator built before the clock starts, so the figures are the steady state of a
long run, where both are amortised over dozens of episodes per house; ``scene_load_s`` gives
that one-off cost separately.

The workload runs on the small houses and on the benchmark's ``mp3d`` houses, each in a fresh
process, so each preset's ``peak_rss_mb`` is its own; ``mp3d_steps_per_s_ratio`` is the mp3d
houses' environment steps per second over the small houses' (large houses must not make a
step much dearer: rendering and geodesic reads should not grow with the house).

``sweep_cost_ratio`` is the time of the MSP sweep (budgets 0-5 of the same episodes, played by
prefix sharing, :mod:`vlln.eval.sweep`) divided by the time of the budget-5 run (the mean of
a run before and one after the sweep, so that a change of load on a shared machine moves
both sides): six independent runs would cost about 6. ``sweep_actions_ratio`` is the same
ratio in actions played, the part of it that does not depend on the machine.
"""

from __future__ import annotations

import multiprocessing
import resource
import tempfile
import time
from pathlib import Path

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import EvalBench
from vlln.eval.config import EvalConfig
from vlln.eval.runner import load_episodes, run_evaluation
from vlln.tasks.metrics import success
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.world.generator.presets import MP3D, SMALL

BENCH_AGENT = "frontier"
BENCH_BUDGET = 5


def compare_presets(settings: EvalBench) -> list[Figure]:
    """Play the workload on the small and the mp3d houses, each in a fresh process, and print
    both presets' figures and the ratio of their environment steps per second."""
    figures: list[Figure] = []
    context = multiprocessing.get_context("spawn")  # a fresh process: its own peak memory
    for preset in (SMALL.name, MP3D.name):
        with context.Pool(1) as pool:
            figures += pool.apply(run_eval_benchmark, (settings, preset))
    rate = {f.metric: f.value for f in figures if f.metric.endswith("env_steps_per_s")}
    ratio = Figure(
        "mp3d_steps_per_s_ratio",
        rate[f"{MP3D.name}_env_steps_per_s"] / rate[f"{SMALL.name}_env_steps_per_s"],
        "x",
    )
    emit(ratio, settings.as_json)
    return [*figures, ratio]


def run_eval_benchmark(settings: EvalBench, preset: str) -> list[Figure]:
    """Play the fixed workload once on the first test house of ``preset`` and print its
    figures, each named ``<preset>_<figure>``."""
    as_json, cache_dir = settings.as_json, settings.cache_dir
    config = EvalConfig(
        agent=BENCH_AGENT,
        task="iign",
        split="test",
        houses=1,
        episodes=settings.episodes,
        budgets=(BENCH_BUDGET,),
        preset=preset,
    )
    figures: list[Figure] = []

    def note(metric: str, value: float, unit: str) -> None:
        figure = Figure(f"{preset}_{metric}", value, unit)
        figures.append(figure)
        emit(figure, as_json)

    scene_ids = {episode.scene_id for episode in load_episodes(config, cache_dir, progress=False)}
    scenes = SceneCache()
    try:
        started = time.perf_counter()
        for scene_id in sorted(scene_ids):
            scenes.get(scene_id)
        note("scene_load_s", time.perf_counter() - started, "s")
        with tempfile.TemporaryDirectory(prefix="vlln-bench-eval-") as out:
            outcome = run_evaluation(
                config, Path(out), cache_dir=cache_dir, progress=False, scenes=scenes
            )
        sweep = config.replace(budgets=tuple(range(BENCH_BUDGET + 1)))
        with tempfile.TemporaryDirectory(prefix="vlln-bench-sweep-") as out:
            swept = run_evaluation(
                sweep, Path(out), cache_dir=cache_dir, progress=False, scenes=scenes
            )
        with tempfile.TemporaryDirectory(prefix="vlln-bench-eval-") as out:
            again = run_evaluation(
                config, Path(out), cache_dir=cache_dir, progress=False, scenes=scenes
            )
    finally:
        scenes.close()
    n = len(outcome.records)
    steps = sum(r.steps for r in outcome.records)
    actions = sum(len(r.actions) for r in outcome.records)
    note("episodes", n, "count")
    note("episodes_per_hour", 3600.0 * n / outcome.seconds, "episodes/h")
    note("seconds_per_episode", outcome.seconds / n, "s")
    note("mean_steps_per_episode", steps / n, "steps")
    note("env_steps_per_s", actions / outcome.seconds, "actions/s")
    note("success_rate", 100.0 * sum(map(success, outcome.records)) / n, "%")
    note("mean_questions_per_episode", sum(len(r.dialog) for r in outcome.records) / n, "count")
    note("sweep_seconds", swept.seconds, "s")
    swept_actions = sum(len(r.actions) for r in swept.records if r.budget == BENCH_BUDGET)
    note("sweep_actions_ratio", _sweep_actions(swept.records) / swept_actions, "x")
    note("sweep_cost_ratio", swept.seconds / ((outcome.seconds + again.seconds) / 2), "x")
    note("peak_rss_mb", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, "MB")
    return figures


def _sweep_actions(records: list[EpisodeRecord]) -> int:
    """Actions the sweep played: the full run, plus each lower budget from the action where
    the full run asked the question it refuses."""
    full = {r.episode_id: r for r in records if r.budget == BENCH_BUDGET}
    total = sum(len(r.actions) for r in full.values())
    for record in records:
        if record.budget == BENCH_BUDGET:
            continue
        talks = [i for i, a in enumerate(full[record.episode_id].actions) if a == "TALK"]
        if record.budget < len(talks):
            total += len(record.actions) - talks[record.budget]
    return total
