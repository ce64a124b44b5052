"""`vlln bench sim --envs N`: simulator steps per second with N environments in N processes.

Each process builds its own house and simulator and replays its own random walk (action,
collision, render and a geodesic query per step, as :func:`vlln.bench.walks.step_fps` does);
all start together after a barrier, and the rate is every process's steps over the time from
the first start to the last finish. On a CPU renderer (Mesa llvmpipe) the rasteriser's threads
are shared out: one environment alone gets every core (``LP_NUM_THREADS``, as a user running one
environment does), each of N processes ``cores // N``. ``envs_speedup`` compares N processes
with one, both measured in the same invocation, ``repeats`` times interleaved (median).

The CPU time per step (every thread of the process, the rasteriser's included) and the part of
it spent on the main thread (Python, vertex shading, binning, read-back) are reported beside
the rates: they do not depend on what else the machine runs, and they bound the speed-up. One
environment alone runs its main thread while its rasteriser threads wait, then its rasteriser
threads while the main thread waits, so a step takes at least ``main + rest / threads``; N
processes that keep every core busy reach ``cores × (main + rest / threads) ÷ CPU per step of
N`` times its rate (``envs_speedup_ceiling``, computed from CPU times alone). The more of one
environment's work runs on the rasteriser's threads, the more cores it keeps busy on its own
and the less N processes can add. ``envs_speedup_same_threads`` compares N processes with one
environment rasterising with as many threads as each of the N does: how the rate grows with
processes at a fixed setting per process.
"""

from __future__ import annotations

import multiprocessing
import os
import statistics
import time
from multiprocessing.synchronize import Barrier
from typing import Any, NamedTuple

import numpy as np

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import SimBench
from vlln.errors import ConfigError

WARM_UP_STEPS = 30


class Run(NamedTuple):
    """One timed run of one or more processes."""

    steps_per_s: float  # all processes together
    cpu_ms_per_step: float  # every thread
    main_thread_cpu_ms_per_step: float  # the thread that steps the simulator


def run_parallel_benchmark(settings: SimBench, envs: int) -> list[Figure]:
    """Print steps/s of one environment, of ``envs`` (``settings.envs``, given) in parallel,
    their ratio and its bound."""
    seed, frames = settings.seed, settings.frames
    cores = len(os.sched_getaffinity(0))  # the cores this process may use (taskset, cgroups)
    threads_alone = cores
    threads_shared = max(1, cores // envs)
    runs_one: list[Run] = []
    runs_many: list[Run] = []
    runs_one_shared: list[Run] = []
    for _ in range(settings.repeats):
        runs_one.append(_run(1, seed, frames, threads_alone))
        runs_many.append(_run(envs, seed, frames, threads_shared))
        if threads_shared != threads_alone:
            runs_one_shared.append(_run(1, seed, frames, threads_shared))
    one, many = _median(runs_one), _median(runs_many)
    one_shared = _median(runs_one_shared) if runs_one_shared else one
    main = one.main_thread_cpu_ms_per_step
    shortest_step_ms = main + (one.cpu_ms_per_step - main) / threads_alone
    figures = [
        Figure("envs", envs, "count"),
        Figure("cpu_cores", cores, "count"),
        Figure("render_threads_1_env", threads_alone, "count"),
        Figure(f"render_threads_per_env_{envs}_envs", threads_shared, "count"),
        Figure("steps_per_s_1_env", one.steps_per_s, "steps/s"),
        Figure(f"steps_per_s_{envs}_envs", many.steps_per_s, "steps/s"),
        Figure("envs_speedup", many.steps_per_s / one.steps_per_s, "x"),
        Figure("cpu_ms_per_step_1_env", one.cpu_ms_per_step, "ms"),
        Figure("main_thread_cpu_ms_per_step_1_env", main, "ms"),
        Figure(f"cpu_ms_per_step_{envs}_envs", many.cpu_ms_per_step, "ms"),
        Figure("cpu_cores_busy_1_env", one.steps_per_s * one.cpu_ms_per_step / 1e3, "cores"),
        Figure(
            f"cpu_cores_busy_{envs}_envs", many.steps_per_s * many.cpu_ms_per_step / 1e3, "cores"
        ),
        Figure("envs_speedup_ceiling", cores * shortest_step_ms / many.cpu_ms_per_step, "x"),
        Figure("steps_per_s_1_env_same_threads", one_shared.steps_per_s, "steps/s"),
        Figure("envs_speedup_same_threads", many.steps_per_s / one_shared.steps_per_s, "x"),
    ]
    for figure in figures:
        emit(figure, settings.as_json)
    return figures


def _median(runs: list[Run]) -> Run:
    """Each figure's median over several runs."""
    return Run(*(statistics.median(values) for values in zip(*runs, strict=True)))


def _run(envs: int, seed: int, frames: int, threads: int) -> Run:
    """Time ``envs`` processes stepping together, each rasterising with ``threads`` threads."""
    context = multiprocessing.get_context("spawn")  # a fresh GL context in every process
    barrier = context.Barrier(envs)
    results: Any = context.Queue()
    workers = [
        context.Process(target=_walk_in_process, args=(seed, i, frames, threads, barrier, results))
        for i in range(envs)
    ]
    for worker in workers:
        worker.start()
    timings = [results.get(timeout=600) for _ in workers]
    for worker in workers:
        worker.join()
    if any(worker.exitcode != 0 for worker in workers):
        raise ConfigError("a benchmark process failed; run `vlln bench sim` alone to see why")
    start = min(t[0] for t in timings)
    end = max(t[1] for t in timings)
    steps = sum(t[2] for t in timings)
    cpu_ms = 1e3 * sum(t[3] for t in timings)
    main_ms = 1e3 * sum(t[4] for t in timings)
    return Run(steps / (end - start), cpu_ms / steps, main_ms / steps)


def _walk_in_process(
    seed: int, index: int, frames: int, threads: int, barrier: Barrier, results: Any
) -> None:
    os.environ["LP_NUM_THREADS"] = str(threads)  # read when the GL context is made
    from vlln.bench.walks import goal_sets, random_walk, step_fps
    from vlln.sim.simulator import Simulator
    from vlln.world.generator import generate_house

    with Simulator(generate_house(seed)) as sim:
        rng = np.random.default_rng([seed, index])
        warm_up = random_walk(sim, rng, WARM_UP_STEPS)
        walk = random_walk(sim, rng, frames)
        goals = goal_sets(sim, rng, count=1)[0]
        step_fps(sim, warm_up, goals)
        barrier.wait()
        start, cpu, main = time.perf_counter(), time.process_time(), time.thread_time()
        step_fps(sim, walk, goals)
        end = time.perf_counter()
        cpu, main = time.process_time() - cpu, time.thread_time() - main
        results.put((start, end, len(walk.actions), cpu, main))
