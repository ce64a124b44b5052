"""`vlln bench sim --envs N`: simulator steps per second with N environments in N processes.

Each process builds its own house and simulator and replays its own random walk (action,
collision, render and a geodesic query per step, as :func:`vlln.bench.sim._step_fps` does);
all start together after a barrier, and the rate is every process's steps over the time from
the first start to the last finish. On a CPU renderer (Mesa llvmpipe) the rasteriser's threads
are shared out: each of N processes gets ``cores // N`` (``LP_NUM_THREADS``), so one
environment alone may use every core. ``envs_speedup`` compares N processes with one, both
measured in the same invocation, ``repeats`` times interleaved (median). The CPU time per
step (every thread of the process, the rasteriser's included) is reported beside the rates:
it does not depend on what else the machine runs, so it shows whether N processes cost more
CPU per step than one when a busy machine hides the speed-up.
"""

from __future__ import annotations

import multiprocessing
import os
import statistics
import time
from multiprocessing.synchronize import Barrier
from typing import Any

import numpy as np

from vlln.bench.figures import Figure, emit
from vlln.errors import ConfigError

WARM_UP_STEPS = 30


def run_parallel_benchmark(
    envs: int, seed: int = 0, frames: int = 300, repeats: int = 3, as_json: bool = False
) -> list[Figure]:
    """Print steps/s of one environment, of ``envs`` in parallel, and their ratio."""
    if envs < 1:
        raise ConfigError(f"--envs must be at least 1, got {envs}")
    cores = len(os.sched_getaffinity(0))  # the cores this process may use (taskset, cgroups)
    one: list[tuple[float, float]] = []
    many: list[tuple[float, float]] = []
    for _ in range(repeats):
        one.append(_steps_per_second(1, seed, frames, cores))
        many.append(_steps_per_second(envs, seed, frames, cores))
    rate_one = statistics.median(rate for rate, _ in one)
    rate_many = statistics.median(rate for rate, _ in many)
    figures = [
        Figure("envs", envs, "count"),
        Figure("cpu_cores", cores, "count"),
        Figure("steps_per_s_1_env", rate_one, "steps/s"),
        Figure(f"steps_per_s_{envs}_envs", rate_many, "steps/s"),
        Figure("envs_speedup", rate_many / rate_one, "x"),
        Figure("cpu_ms_per_step_1_env", statistics.median(cpu for _, cpu in one), "ms"),
        Figure(f"cpu_ms_per_step_{envs}_envs", statistics.median(cpu for _, cpu in many), "ms"),
    ]
    for figure in figures:
        emit(figure, as_json)
    return figures


def _steps_per_second(envs: int, seed: int, frames: int, cores: int) -> tuple[float, float]:
    """(steps per second of all processes together, CPU milliseconds per step)."""
    context = multiprocessing.get_context("spawn")  # a fresh GL context in every process
    barrier = context.Barrier(envs)
    results: Any = context.Queue()
    threads = max(1, cores // envs)
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
    return steps / (end - start), 1e3 * sum(t[3] for t in timings) / steps


def _walk_in_process(
    seed: int, index: int, frames: int, threads: int, barrier: Barrier, results: Any
) -> None:
    os.environ["LP_NUM_THREADS"] = str(threads)  # read when the GL context is made
    from vlln.bench.sim import _goal_sets, _step_fps, _walk
    from vlln.sim.simulator import Simulator
    from vlln.world.generator import generate_house

    with Simulator(generate_house(seed)) as sim:
        rng = np.random.default_rng([seed, index])
        warm_up = _walk(sim, rng, WARM_UP_STEPS)
        walk = _walk(sim, rng, frames)
        goals = _goal_sets(sim, rng, count=1)[0]
        _step_fps(sim, warm_up, goals)
        barrier.wait()
        start, cpu = time.perf_counter(), time.process_time()
        _step_fps(sim, walk, goals)
        end, cpu = time.perf_counter(), time.process_time() - cpu
        results.put((start, end, len(walk.actions), cpu))
