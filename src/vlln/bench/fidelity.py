"""``vlln bench fidelity``: how hard the benchmark is, next to the paper's Table 1.

It plays the paper's table of non-learned baselines on the same episodes of the paper's test
protocol (``--split test500``: the 14 test houses of the ``mp3d`` preset), on ObjectNav, IGN
and IIGN, every one with a detector that sees no privileged labels (our ``noisy`` detector):
the paper's FBE (``fbe``, which never asks), the VLFM-style value-map agent (``vlfm``), our
frontier agent with questions (``frontier``: IIGN at dialog budgets 0 to 5, played by prefix
sharing, whose records equal independent runs'; IGN at budget 5; ObjectNav has no dialog, so
there the frontier agent is FBE), and the
privileged shortest-path expert. Every run is an ordinary run directory under ``--out``, so a
killed benchmark resumes where it stopped and the runs can be scored, reported and filmed like
any other.

For each task and budget it prints SR and SPL with 95 % intervals (Wilson's interval for the
success rate, Student's t for the mean SPL), the failure taxonomy's shares, and for IIGN the
paper's MSP over budgets 0..5 and the dialog gain (SR at budget 5 minus SR at budget 0), each
over the same episodes with a paired 95 % interval; and every agent's SR minus FBE's on the
same episodes, with a paired interval.
"""

from __future__ import annotations

import json
import math
import multiprocessing
import statistics
import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from scipy import stats

from vlln.bench.settings import FidelityBench
from vlln.eval.config import EvalConfig
from vlln.eval.results import RunDirectory
from vlln.eval.runner import load_episodes, run_evaluation
from vlln.tasks.metrics import record_spl, success
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import default_cache_dir
from vlln.tasks.splits import TEST_PROTOCOL_SPLIT
from vlln.tasks.taxonomy import CLASS_ABBREVIATIONS, FAILURE_CLASSES, classify

CONFIDENCE = 0.95
BASELINE = "fbe"  # the paper's frontier baseline, which every other agent is compared with


@dataclass(frozen=True)
class FidelityRun:
    """One run of the benchmark: an agent (and detector) on a task at some budgets."""

    agent: str
    detector: str | None
    task: str
    budgets: tuple[int, ...]

    @property
    def folder(self) -> str:
        detector = f"_{self.detector}" if self.detector else ""
        return f"{self.agent}{detector}_{self.task}"

    def config(self, episodes: int, preset: str) -> EvalConfig:
        return EvalConfig(
            agent=self.agent,
            task=self.task,
            split=TEST_PROTOCOL_SPLIT,
            episodes=episodes,
            budgets=self.budgets,
            detector=self.detector,
            preset=preset,
        )


RUNS: tuple[FidelityRun, ...] = (  # the longest first, so parallel workers end together
    FidelityRun("frontier", "noisy", "iign", (0, 1, 2, 3, 4, 5)),  # with questions
    FidelityRun("frontier", "noisy", "ign", (5,)),
    FidelityRun("vlfm", "noisy", "iign", (0,)),
    FidelityRun("vlfm", "noisy", "ign", (0,)),
    FidelityRun("fbe", "noisy", "iign", (0,)),
    FidelityRun("fbe", "noisy", "ign", (0,)),
    FidelityRun("vlfm", "noisy", "objectnav", (0,)),
    FidelityRun("fbe", "noisy", "objectnav", (0,)),
    FidelityRun("expert", None, "objectnav", (0,)),
    FidelityRun("expert", None, "ign", (0,)),
    FidelityRun("expert", None, "iign", (0,)),
)


@dataclass(frozen=True)
class Interval:
    """A figure and its 95 % interval."""

    value: float
    low: float
    high: float

    def to_json(self) -> dict[str, float]:
        return {
            "value": round(self.value, 2),
            "low": round(self.low, 2),
            "high": round(self.high, 2),
        }


def success_interval(successes: int, n: int) -> Interval:
    """SR in % with Wilson's 95 % score interval (sound near 0 % and 100 %, unlike Wald's)."""
    ci = stats.binomtest(successes, n).proportion_ci(CONFIDENCE, method="wilson")
    return Interval(100.0 * successes / n, 100.0 * ci.low, 100.0 * ci.high)


def mean_interval(values: Sequence[float]) -> Interval:
    """The mean with Student's t 95 % interval (a point when there is one value or no spread)."""
    mean = statistics.fmean(values)
    if len(values) < 2 or statistics.pstdev(values) == 0.0:
        return Interval(mean, mean, mean)
    sem = statistics.stdev(values) / math.sqrt(len(values))
    half = float(stats.t.ppf(0.5 + CONFIDENCE / 2.0, len(values) - 1)) * sem
    return Interval(mean, mean - half, mean + half)


def group_figures(records: Sequence[EpisodeRecord]) -> dict[str, object]:
    """SR and SPL with intervals, and the share of each failure class, of one group."""
    n = len(records)
    outcomes = Counter(classify(r) for r in records)
    return {
        "n": n,
        "sr": success_interval(sum(success(r) for r in records), n).to_json(),
        "spl": mean_interval([100.0 * record_spl(r) for r in records]).to_json(),
        "taxonomy": {
            CLASS_ABBREVIATIONS[name]: round(100.0 * outcomes[name] / n, 2)
            for name in FAILURE_CLASSES
        },
    }


def paired_difference(
    base: Sequence[EpisodeRecord], other: Sequence[EpisodeRecord]
) -> Interval | None:
    """SR of ``other`` minus SR of ``base`` over the episodes both played, with a paired 95 %
    interval, in percentage points (each record list holds one budget)."""
    before = {(r.scene_id, r.episode_id): success(r) for r in base}
    after = {(r.scene_id, r.episode_id): success(r) for r in other}
    shared = sorted(set(before) & set(after))
    if not shared:
        return None
    return mean_interval([100.0 * (after[k] - before[k]) for k in shared])


def dialog_gain(records: Sequence[EpisodeRecord], low: int, high: int) -> Interval | None:
    """SR at budget ``high`` minus SR at ``low`` on the episodes played at both, with a paired
    95 % interval, in percentage points."""
    at = {budget: [r for r in records if r.budget == budget] for budget in (low, high)}
    return paired_difference(at[low], at[high])


def msp_interval(records: Sequence[EpisodeRecord], budgets: Sequence[int]) -> Interval | None:
    """MSP over ``budgets`` (0..n) with a paired 95 % interval, in percentage points: per
    episode played at every budget, the mean over i = 1..n of success at i minus success at 0
    (the paper's MSP is the mean of these over the episodes)."""
    low, rest = min(budgets), sorted(set(budgets) - {min(budgets)})
    if not rest:
        return None
    by_episode: dict[tuple[str, str], dict[int, bool]] = {}
    for record in records:
        by_episode.setdefault((record.scene_id, record.episode_id), {})[record.budget] = success(
            record
        )
    gains = [
        100.0 * sum(played[b] - played[low] for b in rest) / len(rest)
        for played in by_episode.values()
        if all(b in played for b in (low, *rest))
    ]
    return mean_interval(gains) if gains else None


def _play(
    job: tuple[FidelityRun, int, str, str, str | None], scenes: SceneCache | None = None
) -> str:
    run, episodes, preset, out, cache_dir = job
    config = run.config(episodes, preset)
    cache = None if cache_dir is None else Path(cache_dir)
    outcome = run_evaluation(
        config, Path(out) / run.folder, cache_dir=cache, progress=False, scenes=scenes
    )
    return f"{run.folder}: {len(outcome.records)} of {outcome.planned} episode lines"


def run_fidelity_benchmark(settings: FidelityBench) -> list[dict[str, object]]:
    """Play (or resume) every run of :data:`RUNS` into ``settings.out`` and print the figures."""
    out, episodes, preset = settings.out, settings.episodes, settings.preset
    workers, cache_dir = settings.workers, settings.cache_dir
    cache = None if cache_dir is None else str(cache_dir)
    jobs = [(run, episodes, preset, str(out), cache) for run in RUNS]
    # Every task's episodes are built once, before the workers share the cache.
    for task in sorted({run.task for run in RUNS}):
        config = RUNS[0].config(episodes, preset)
        load_episodes(
            config.replace(task=task, budgets=(0,)),
            cache_dir or default_cache_dir(),
            progress=False,
        )
    if workers == 1:  # the runs share the houses: each run plays the same episodes
        scenes = SceneCache()
        try:
            done = [_play(job, scenes) for job in jobs]
        finally:
            scenes.close()
    else:  # spawned, not forked: a forked child would share the parent's GL state
        # One process per run (maxtasksperchild): each run's memory is its own.
        with multiprocessing.get_context("spawn").Pool(workers, maxtasksperchild=1) as pool:
            done = pool.map(_play, jobs, chunksize=1)
    for line in done:
        print(f"fidelity: {line}", file=sys.stderr)
    records = {run: RunDirectory(out / run.folder).records() for run in RUNS}
    rows = [row for run in RUNS for row in fidelity_rows(run, records[run])]
    rows += comparison_rows(records)
    for row in rows:
        print(json.dumps(row) if settings.as_json else _table_line(row))
    return rows


def fidelity_rows(run: FidelityRun, records: Sequence[EpisodeRecord]) -> list[dict[str, object]]:
    """One row per budget of a run, and for IIGN the dialog gain between its budgets."""
    label = _label(run)
    rows: list[dict[str, object]] = []
    for budget in run.budgets:
        group = [r for r in records if r.budget == budget]
        if group:
            rows.append(
                {"agent": label, "task": run.task, "budget": budget, **group_figures(group)}
            )
    if len(run.budgets) > 2:
        msp = msp_interval(records, run.budgets)
        if msp is not None:
            rows.append({"agent": label, "task": run.task, "msp_pp": msp.to_json()})
    if len(run.budgets) > 1:
        gain = dialog_gain(records, min(run.budgets), max(run.budgets))
        if gain is not None:
            budgets = [min(run.budgets), max(run.budgets)]
            rows.append(
                {
                    "agent": label,
                    "task": run.task,
                    "dialog_gain_pp": gain.to_json(),
                    "budgets": budgets,
                }
            )
    return rows


def comparison_rows(records: dict[FidelityRun, list[EpisodeRecord]]) -> list[dict[str, object]]:
    """Each baseline against the paper's FBE on every task: the paired SR difference over the
    episodes both played (the other's highest budget against FBE's budget 0)."""
    rows: list[dict[str, object]] = []
    for base in (run for run in RUNS if run.agent == BASELINE):
        for run in RUNS:
            if run.task != base.task or run.agent in (BASELINE, "expert"):
                continue
            top = max(run.budgets)
            other = [r for r in records[run] if r.budget == top]
            difference = paired_difference(records[base], other)
            if difference is not None:
                rows.append(
                    {
                        "agent": _label(run),
                        "task": run.task,
                        "budget": top,
                        "sr_minus_fbe_pp": difference.to_json(),
                    }
                )
    return rows


def _label(run: FidelityRun) -> str:
    return run.agent + (f" ({run.detector} detector)" if run.detector else "")


def _table_line(row: dict[str, object]) -> str:
    """One row as a line of text (``--json`` prints the row itself)."""
    head = f"{row['agent']:<28} {row['task']:<9}"
    if "msp_pp" in row:
        return f"{head} MSP {row['msp_pp']} pp"
    if "sr_minus_fbe_pp" in row:
        return f"{head} SR minus FBE's {row['sr_minus_fbe_pp']} pp (budget {row['budget']})"
    if "dialog_gain_pp" in row:
        gain = row["dialog_gain_pp"]
        return f"{head} dialog gain {gain} pp (budgets {row['budgets']})"
    return (
        f"{head} b{row['budget']} n={row['n']} SR {row['sr']} SPL {row['spl']} "
        f"taxonomy {row['taxonomy']}"
    )
