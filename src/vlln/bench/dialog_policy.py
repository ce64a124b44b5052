"""``vlln bench dialog-policy``: a learned dialog policy against the fixed triggers.

Two ``vlln eval`` runs of the frontier agent on the same episodes (one without
``--dialog-policy``, one with it) are paired episode by episode: SR with Wilson intervals,
questions per episode with t intervals, and the paired differences (learned − fixed) with
paired 95 % intervals (:func:`vlln.bench.fidelity.paired_difference`). Only episodes both
runs played count, so a run cut short compares on what it finished.
"""

from __future__ import annotations

import json
from collections.abc import Sequence

from vlln.bench.fidelity import mean_interval, paired_difference, success_interval
from vlln.bench.settings import DialogPolicyFigures
from vlln.eval.results import load_run_records
from vlln.tasks.metrics import success
from vlln.tasks.record import EpisodeRecord

Key = tuple[str, str]


def _by_episode(records: Sequence[EpisodeRecord], budget: int) -> dict[Key, EpisodeRecord]:
    return {(r.scene_id, r.episode_id): r for r in records if r.budget == budget}


def compare(
    fixed: Sequence[EpisodeRecord], learned: Sequence[EpisodeRecord], budget: int
) -> dict[str, object]:
    """The figures of both runs at ``budget`` over the episodes both played."""
    before, after = _by_episode(fixed, budget), _by_episode(learned, budget)
    shared = sorted(set(before) & set(after))
    figures: dict[str, object] = {"budget": budget, "n": len(shared)}
    if not shared:
        return figures
    for name, run in (("fixed", before), ("learned", after)):
        records = [run[k] for k in shared]
        figures[name] = {
            "sr": success_interval(sum(success(r) for r in records), len(records)).to_json(),
            "questions": mean_interval([float(len(r.dialog)) for r in records]).to_json(),
        }
    gain = paired_difference([before[k] for k in shared], [after[k] for k in shared])
    figures["sr_difference"] = None if gain is None else gain.to_json()
    saved = [float(len(after[k].dialog) - len(before[k].dialog)) for k in shared]
    figures["questions_difference"] = mean_interval(saved).to_json()
    mean_fixed = sum(len(before[k].dialog) for k in shared) / len(shared)
    mean_learned = sum(len(after[k].dialog) for k in shared) / len(shared)
    if mean_fixed > 0:
        figures["fewer_questions_percent"] = round(100.0 * (1.0 - mean_learned / mean_fixed), 1)
    return figures


def _interval(value: object) -> str:
    if not isinstance(value, dict):
        return "–"
    return f"{value['value']:.2f} [{value['low']:.2f}, {value['high']:.2f}]"


def run_dialog_policy_figures(settings: DialogPolicyFigures) -> dict[str, object]:
    """Print the comparison of the two runs (a table, or one JSON line with --json)."""
    figures = compare(
        load_run_records([settings.fixed]), load_run_records([settings.learned]), settings.budget
    )
    if settings.as_json:
        print(json.dumps(figures))
        return figures
    print(f"frontier agent, budget {settings.budget}: {figures['n']} episodes played by both")
    print("| dialog policy | SR % [95 % CI] | questions / episode [95 % CI] |")
    print("| --- | --- | --- |")
    for name in ("fixed", "learned"):
        run = figures.get(name)
        if isinstance(run, dict):
            print(f"| {name} | {_interval(run['sr'])} | {_interval(run['questions'])} |")
    print(
        f"| learned − fixed (paired) | {_interval(figures.get('sr_difference'))} | "
        f"{_interval(figures.get('questions_difference'))} |"
    )
    if "fewer_questions_percent" in figures:
        print(f"questions: {figures['fewer_questions_percent']} % fewer with the learned policy")
    return figures
