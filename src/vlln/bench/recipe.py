"""`vlln bench recipe-figures`: the held-out figures of ``scripts/cpu-recipe.sh``.

The recipe leaves one run per agent and task under ``OUT/eval`` (``iign-model``,
``iign-random``, ``iign-fbe``, ``iign-teacher``, the same for ``objectnav``) and one per
checkpoint (``curve-STEPS``), each a run directory or a folder of its shards (``shard-*``).
This prints, as Markdown:

* SR and SPL with 95 % intervals (Wilson for SR, Student's t for SPL) of every run and budget,
  with the questions asked per episode and the failure classes;
* the paired dialog gain of each IIGN run (SR at budget 5 minus SR at budget 0 on the same
  episodes) and the paired SR difference between the model and FBE;
* the learning curve, one row per checkpoint: held-out IIGN SR at budget 5 (the last
  checkpoint's is the ``iign-model`` run's) and the share of the teacher's decisions the
  checkpoint makes alike on the training export's prompts and on an export of held-out
  houses (``OUT/agreement/STEPS-train.jsonl`` and ``STEPS-heldout.jsonl``, the output of
  ``vlln bench agreement --json``): agreement rises before SR does.
"""

from __future__ import annotations

import statistics
from collections import Counter
from collections.abc import Sequence
from pathlib import Path

from vlln.bench.fidelity import (
    Interval,
    dialog_gain,
    mean_interval,
    paired_difference,
    success_interval,
)
from vlln.bench.settings import RecipeFigures
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.results import load_run_records
from vlln.files import ReadCap, parse_json
from vlln.tasks.metrics import record_spl, success
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.taxonomy import CLASS_ABBREVIATIONS, FAILURE_CLASSES, SUCCESS, classify

AGENTS = ("model", "random", "fbe", "teacher")
TASKS = ("iign", "objectnav")
SPLITS = ("train", "heldout")  # the agreement files' suffixes
# An agreement file is a few lines of figures.
_AGREEMENT_CAP = ReadCap("an agreement file", 1)


def print_recipe_figures(settings: RecipeFigures) -> None:
    print(recipe_figures(settings.out))


def recipe_figures(out: Path) -> str:
    """The Markdown of every held-out figure the recipe in ``out`` has made so far."""
    runs = out / "eval"
    if not runs.is_dir():
        raise ConfigError(f"{runs} does not exist; run scripts/cpu-recipe.sh with OUT={out}")
    lines: list[str] = []
    for task in TASKS:
        found = {
            a: _records(runs / f"{task}-{a}") for a in AGENTS if (runs / f"{task}-{a}").is_dir()
        }
        if not found:
            continue
        lines += [f"## {task.upper()} on held-out houses", "", _run_table(found), ""]
        lines += _comparisons(task, found)
    lines += _curve(out)
    return "\n".join(lines)


def _curve(out: Path) -> list[str]:
    """The learning curve's table (module doc), or nothing before any checkpoint is measured."""
    runs = out / "eval"
    played = {int(run.name.split("-")[1]): run for run in runs.glob("curve-*")}
    checkpoints = [int(path.name.split("-")[1]) for path in out.glob("model/checkpoint-*")]
    if checkpoints and (runs / "iign-model").is_dir():
        played[max(checkpoints)] = runs / "iign-model"
    agreement = {
        tuple(path.stem.split("-")): _agreement(path)
        for path in (out / "agreement").glob("*-*.jsonl")
    }
    steps = sorted(set(played) | {int(step) for step, _ in agreement})
    if not steps:
        return []
    lines = [
        "## Learning curve (IIGN, budget 5)",
        "",
        "| steps | n | SR % [95 % CI] | agreement, training prompts % | agreement, held-out % |",
        "| --- | --- | --- | --- | --- |",
    ]
    for step in steps:
        records = [r for r in _records(played[step]) if r.budget == 5] if step in played else []
        train, held_out = (agreement.get((str(step), split), "-") for split in SPLITS)
        lines.append(f"| {step} | {len(records)} | {_sr(records)} | {train} | {held_out} |")
    return [*lines, ""]


def _agreement(path: Path) -> str:
    """The ``action_agreement`` figure of a ``vlln bench agreement --json`` output."""
    for line in _AGREEMENT_CAP.read(path).splitlines():
        try:
            figure = parse_json(line)
            if figure.get("metric") == "action_agreement":
                return f"{float(figure['value']):.1f}"
        except (ValueError, AttributeError, KeyError, TypeError) as error:
            raise DataFormatError(
                f"{path} is not an output of vlln bench agreement --json ({error}); "
                "run vlln bench agreement again"
            ) from None
    raise ConfigError(f"{path} has no action_agreement figure; run vlln bench agreement again")


def _records(run: Path) -> list[EpisodeRecord]:
    """The records of a run directory, or of its shards (``shard-*``) together."""
    return load_run_records(sorted(run.glob("shard-*")) or [run])


def _run_table(found: dict[str, list[EpisodeRecord]]) -> str:
    failures = [name for name in FAILURE_CLASSES if name != SUCCESS]
    classes = [CLASS_ABBREVIATIONS[name] for name in failures]
    rows = [
        "| run | budget | n | SR % [95 % CI] | SPL % [95 % CI] | questions asked | "
        + " | ".join(f"{c} %" for c in classes)
        + " |",
        "| --- " * (6 + len(classes)) + "|",
    ]
    for agent, records in found.items():
        for budget in sorted({r.budget for r in records}):
            group = [r for r in records if r.budget == budget]
            outcomes = Counter(classify(r) for r in group)
            shares = [f"{100.0 * outcomes[name] / len(group):.1f}" for name in failures]
            spl = _clamped(mean_interval([100.0 * record_spl(r) for r in group]), 0.0)
            questions = statistics.fmean(len(r.dialog) for r in group)
            rows.append(
                f"| {agent} | {budget} | {len(group)} | {_sr(group)} | {_format(spl)} | "
                f"{questions:.2f} | " + " | ".join(shares) + " |"
            )
    return "\n".join(rows)


def _comparisons(task: str, found: dict[str, list[EpisodeRecord]]) -> list[str]:
    """Paired dialog gains (IIGN) and the model's paired SR difference from FBE."""
    lines: list[str] = []
    if task == "iign":
        for agent, records in found.items():
            gain = dialog_gain(records, 0, 5)
            if gain is not None:
                lines.append(
                    f"- {agent}: dialog gain (SR at budget 5 - budget 0, paired) "
                    f"{_format(gain)} points"
                )
    if "model" in found and "fbe" in found:
        budget = 5 if task == "iign" else 0
        model = [r for r in found["model"] if r.budget == budget]
        fbe = [r for r in found["fbe"] if r.budget == budget]
        difference = paired_difference(fbe, model)
        if difference is not None:
            shown = _format(_clamped(difference, -100.0))
            lines.append(f"- model - FBE, budget {budget} (paired): {shown} points")
    return [*lines, ""] if lines else []


def _sr(records: Sequence[EpisodeRecord]) -> str:
    if not records:
        return "-"
    return _format(success_interval(sum(success(r) for r in records), len(records)))


def _format(interval: Interval) -> str:
    return f"{interval.value:.1f} [{interval.low:.1f}, {interval.high:.1f}]"


def _clamped(interval: Interval, lowest: float) -> Interval:
    """A t interval cut to the values the quantity can take (lowest to 100)."""
    return Interval(interval.value, max(lowest, interval.low), min(100.0, interval.high))
