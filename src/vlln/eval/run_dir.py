"""The run directory's file names and ``run.json``'s fields, in one place: the runner and the
web study write them, ``vlln score``, ``vlln report``, ``vlln video``, the benchmarks and
resumes read them, and all of them take the names from here.

Layout::

    DIR/run.json        the run's arguments (EvalConfig); a restart must match them, plus
                        the facts in RUN_FACTS (planned lines, plan, provenance)
    DIR/episodes.jsonl  one EpisodeRecord.to_json() per line, in the order played (plan order)
    DIR/summary.json    every metric, recomputed from episodes.jsonl (see vlln.eval.summary)
    DIR/summary.md      the same as Markdown tables
    DIR/.lock           held while a process writes here, so two runs cannot interleave

    DIR/episodes.skipped.jsonl  lines set aside: invalid, repeated, unplanned or of another run
    DIR/episodes.refused.jsonl  episodes refused as unplayable in their scene (vlln.eval.refusals)

The layout is the one docs/reference-formats.md describes; the readers and writers of each
file are :mod:`vlln.eval.results` (run.json, episode lines), :mod:`vlln.eval.refusals` and
:mod:`vlln.eval.plan` (the plan's fields).
"""

from __future__ import annotations

from pathlib import Path

RUN_FILE = "run.json"
EPISODES_FILE = "episodes.jsonl"
SKIPPED_FILE = "episodes.skipped.jsonl"
REFUSED_FILE = "episodes.refused.jsonl"
SUMMARY_JSON = "summary.json"
SUMMARY_MD = "summary.md"
LOCK_FILE = ".lock"

# Facts kept in run.json that are not arguments of the run.
PLANNED_FACT = "planned_episodes"  # episode lines this run (shard) plans
PLAN_FACT = "plan"  # the plan (vlln.eval.plan.RunPlan.to_json)
PROVENANCE_FACT = "provenance"  # agent, oracle, backend, model
RUN_FACTS = (PLANNED_FACT, PLAN_FACT, PROVENANCE_FACT)

# Fields of the plan.
PLAN_EPISODES = "episodes"  # [[scene_id, episode_id], ...] of this shard
PLAN_ALL_SHARDS = "all_shards"  # episode lines planned by every shard of the run together


def run_file(run_dir: Path) -> Path:
    return run_dir / RUN_FILE


def episodes_file(run_dir: Path) -> Path:
    return run_dir / EPISODES_FILE


def summary_md_file(run_dir: Path) -> Path:
    return run_dir / SUMMARY_MD
