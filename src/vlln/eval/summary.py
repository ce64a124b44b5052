"""Run summaries: every metric of a set of episode records, as JSON and as Markdown.

``vlln eval`` writes them after a run and ``vlln score`` recomputes them from episode lines
alone, through the same function, so the two always agree. Records are put in a canonical
order first (agent, task, budget, scene, episode), which makes a summary independent of the
order episodes finished in: a resumed run, a sharded run merged, and an uninterrupted run give
byte-identical summaries.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field
from typing import Any

from vlln.errors import ConfigError
from vlln.eval.results import record_key
from vlln.tasks.aggregate import (
    BudgetSweep,
    MetricSummary,
    format_table,
    summarize_budgets,
    summarize_by,
)
from vlln.tasks.metrics import ORACLE_SUCCESS_RADIUS, SUCCESS_RADIUS
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.taxonomy import STOP_RADIUS


@dataclass(frozen=True)
class GroupSummary:
    """One agent on one task: a summary per dialog budget (MSP when complete) and per
    target category at each budget."""

    agent: str
    task: str
    sweep: BudgetSweep
    per_category: dict[int, dict[str, MetricSummary]]
    # Failed actions per budget and kind ("parse", "server", "goal", "invalid"): a model
    # agent's unreadable replies and server failures, each of which wasted a step.
    failed_actions: dict[int, dict[str, int]] = field(default_factory=dict)

    @property
    def label(self) -> str:
        return f"{self.agent} on {self.task.upper()}"


def summarize_run(
    records: Iterable[EpisodeRecord],
    success_radius: float = SUCCESS_RADIUS,
    os_radius: float = ORACLE_SUCCESS_RADIUS,
    stop_radius: float = STOP_RADIUS,
) -> list[GroupSummary]:
    """Summaries of ``records`` grouped by (agent, task), in canonical order."""
    ordered = sorted(records, key=record_key)
    if not ordered:
        raise ConfigError("no finished episodes to summarize; run vlln eval first")
    groups: dict[tuple[str, str], list[EpisodeRecord]] = {}
    for record in ordered:
        groups.setdefault((record.agent, record.task), []).append(record)
    summaries = []
    for (agent, task), group in groups.items():
        sweep = summarize_budgets(group, success_radius, os_radius, stop_radius)
        per_category = {
            budget: summarize_by(
                [record for record in group if record.budget == budget],
                success_radius=success_radius,
                os_radius=os_radius,
                stop_radius=stop_radius,
            )
            for budget in sweep.by_budget
        }
        failed = {
            budget: failed_action_counts(r for r in group if r.budget == budget)
            for budget in sweep.by_budget
        }
        summaries.append(GroupSummary(agent, task, sweep, per_category, failed))
    return summaries


def failed_action_counts(records: Iterable[EpisodeRecord]) -> dict[str, int]:
    """Failed actions by kind over ``records``, kinds sorted; records written before kinds
    were kept count their failed actions as ``unknown``."""
    counts: dict[str, int] = {}
    for record in records:
        kinds = record.failures or (
            {"unknown": record.failed_actions} if record.failed_actions else {}
        )
        for kind, count in kinds.items():
            counts[kind] = counts.get(kind, 0) + count
    return dict(sorted(counts.items()))


def failed_actions_line(counts: dict[str, int]) -> str:
    """``"parse 3, server 1"``, or ``"none"``."""
    return ", ".join(f"{kind} {count}" for kind, count in counts.items()) or "none"


def summary_json(groups: list[GroupSummary]) -> dict[str, Any]:
    """A JSON-ready summary (NaN written as null); radii stated once at the top."""
    first = next(iter(groups[0].sweep.by_budget.values()))
    return {
        "success_radius": first.success_radius,
        "os_radius": first.os_radius,
        "stop_radius": first.stop_radius,
        "groups": [
            {
                "agent": group.agent,
                "task": group.task,
                "msp": group.sweep.msp,
                "budgets": {
                    str(budget): {
                        "overall": _metrics_json(summary),
                        "failed_actions": group.failed_actions.get(budget, {}),
                        "per_category": {
                            name: _metrics_json(row)
                            for name, row in group.per_category[budget].items()
                        },
                    }
                    for budget, summary in group.sweep.by_budget.items()
                },
            }
            for group in groups
        ],
    }


def _metrics_json(summary: MetricSummary) -> dict[str, Any]:
    data = asdict(summary)
    for radius in ("success_radius", "os_radius", "stop_radius"):
        del data[radius]
    return {
        name: None if isinstance(value, float) and math.isnan(value) else value
        for name, value in data.items()
    }


def summary_markdown(groups: list[GroupSummary], title: str = "Evaluation summary") -> str:
    """Markdown: overall table per budget, SR against budget with MSP, and per category at the
    largest budget (every budget's categories are in the JSON summary)."""
    first = next(iter(groups[0].sweep.by_budget.values()))
    lines = [
        f"# {title}",
        "",
        f"Success: STOP closer than {first.success_radius:.2f} m (geodesic) to a goal view "
        f"point. OS (oracle success) radius: {first.os_radius:.2f} m, the reference "
        "evaluator's value, which is why OS sits far above SR.",
    ]
    for group in groups:
        lines += ["", f"## {group.label}", "", "### Overall", ""]
        rows = {f"budget {b}": s for b, s in group.sweep.by_budget.items()}
        lines.append(format_table(rows))
        failed = {b: c for b, c in group.failed_actions.items() if c}
        if failed:
            lines.append("")
            lines += [
                f"Failed actions at budget {b}: {failed_actions_line(c)}."
                for b, c in failed.items()
            ]
        if len(group.sweep.by_budget) > 1:
            lines += ["", "### Success rate against dialog budget", ""]
            lines += budget_table(group.sweep)
        largest = max(group.per_category)
        lines += ["", f"### Per target category (budget {largest})", ""]
        lines.append(format_table(group.per_category[largest]))
    return "\n".join(lines) + "\n"


def budget_table(sweep: BudgetSweep) -> list[str]:
    """SR per budget as a Markdown table plus the MSP line."""
    lines = ["| budget | n | SR | SPL | OS |", "| --- | --- | --- | --- | --- |"]
    for budget, summary in sweep.by_budget.items():
        lines.append(
            f"| {budget} | {summary.n} | {summary.sr:.2f} | {summary.spl:.2f} | {summary.os:.2f} |"
        )
    lines.append("")
    if sweep.msp is None:
        lines.append(
            "MSP: not defined here; it needs budgets 0..n (n >= 1) over the same episodes."
        )
    else:
        n = max(sweep.by_budget)
        lines.append(f"MSP (budgets 0..{n}): {sweep.msp:.2f} percentage points of SR.")
    return lines
