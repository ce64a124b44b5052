"""Benchmark tables: per-episode metrics averaged over sets of episode records.

Percent convention: SR, SPL, OS and the failure-class shares are percentages (0-100), as the
paper reports them; NE is in metres; MSP is in percentage points. NE is the mean over episodes
whose final position can reach a goal; the others are counted in ``ne_unreachable`` and
reported, never silently dropped. Every summary carries the radii it was computed with, so a
table can state them.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass

from vlln.errors import ConfigError
from vlln.tasks.metrics import (
    ORACLE_SUCCESS_RADIUS,
    SUCCESS_RADIUS,
    msp,
    navigation_error,
    oracle_success,
    record_spl,
    success,
)
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.taxonomy import CLASS_ABBREVIATIONS, FAILURE_CLASSES, STOP_RADIUS, classify


@dataclass(frozen=True)
class MetricSummary:
    """Aggregate metrics of ``n`` episodes (SR, SPL, OS in percent; NE in metres)."""

    n: int
    sr: float
    spl: float
    os: float
    ne: float  # mean over reachable final positions; nan when none is reachable
    ne_unreachable: int  # episodes whose final position cannot reach a goal
    mean_steps: float  # counted steps
    mean_questions: float  # questions asked, including those refused beyond the budget
    failures: dict[str, int]  # episodes per class of FAILURE_CLASSES (success included)
    success_radius: float
    os_radius: float
    stop_radius: float

    def class_percent(self, name: str) -> float:
        """Share of episodes in class ``name`` (one of FAILURE_CLASSES), percent."""
        if name not in self.failures:
            raise ConfigError(f"unknown outcome class {name!r}; choose from {FAILURE_CLASSES}")
        return 100.0 * self.failures[name] / self.n


@dataclass(frozen=True)
class BudgetSweep:
    """One summary per dialog budget and, when the sweep is complete, its MSP.

    ``msp`` (percentage points) is set only when budgets ``0..n`` (n >= 1) are all present and
    every budget covers the same episodes; otherwise it is ``None``.
    """

    by_budget: dict[int, MetricSummary]
    msp: float | None


def summarize(
    records: Iterable[EpisodeRecord],
    success_radius: float = SUCCESS_RADIUS,
    os_radius: float = ORACLE_SUCCESS_RADIUS,
    stop_radius: float = STOP_RADIUS,
) -> MetricSummary:
    """Average every metric over ``records`` (at least one)."""
    episodes = list(records)
    if not episodes:
        raise ConfigError("no episode records to summarize; pass at least one record")
    n = len(episodes)
    errors = [navigation_error(record) for record in episodes]
    reachable = [error for error in errors if math.isfinite(error)]
    failures = dict.fromkeys(FAILURE_CLASSES, 0)
    for record in episodes:
        failures[classify(record, success_radius, stop_radius)] += 1
    return MetricSummary(
        n=n,
        sr=100.0 * sum(success(record, success_radius) for record in episodes) / n,
        spl=100.0 * sum(record_spl(record, success_radius) for record in episodes) / n,
        os=100.0 * sum(oracle_success(record, os_radius) for record in episodes) / n,
        ne=sum(reachable) / len(reachable) if reachable else math.nan,
        ne_unreachable=n - len(reachable),
        mean_steps=sum(record.steps for record in episodes) / n,
        mean_questions=sum(len(record.dialog) for record in episodes) / n,
        failures=failures,
        success_radius=success_radius,
        os_radius=os_radius,
        stop_radius=stop_radius,
    )


def summarize_by(
    records: Iterable[EpisodeRecord],
    key: Callable[[EpisodeRecord], str] = lambda record: record.object_category,
    success_radius: float = SUCCESS_RADIUS,
    os_radius: float = ORACLE_SUCCESS_RADIUS,
    stop_radius: float = STOP_RADIUS,
) -> dict[str, MetricSummary]:
    """One summary per label that ``key`` gives (default: the target category), first-seen order."""
    groups: dict[str, list[EpisodeRecord]] = {}
    for record in records:
        groups.setdefault(key(record), []).append(record)
    return {
        name: summarize(group, success_radius, os_radius, stop_radius)
        for name, group in groups.items()
    }


def summarize_budgets(
    records: Iterable[EpisodeRecord],
    success_radius: float = SUCCESS_RADIUS,
    os_radius: float = ORACLE_SUCCESS_RADIUS,
    stop_radius: float = STOP_RADIUS,
) -> BudgetSweep:
    """Summaries per dialog budget (ascending) of one agent on one task, plus MSP over SR."""
    episodes = list(records)
    for field_name in ("agent", "task"):
        values = sorted({getattr(record, field_name) for record in episodes})
        if len(values) > 1:
            raise ConfigError(
                f"a budget sweep compares one {field_name}, got {values}; "
                f"filter the records to one {field_name} first"
            )
    groups: dict[int, list[EpisodeRecord]] = {}
    for record in sorted(episodes, key=lambda record: record.budget):
        groups.setdefault(record.budget, []).append(record)
    by_budget = {
        budget: summarize(group, success_radius, os_radius, stop_radius)
        for budget, group in groups.items()
    }
    return BudgetSweep(by_budget=by_budget, msp=_sweep_msp(groups, by_budget))


def _sweep_msp(
    groups: Mapping[int, Sequence[EpisodeRecord]], by_budget: Mapping[int, MetricSummary]
) -> float | None:
    budgets = list(by_budget)
    if len(budgets) < 2 or budgets != list(range(len(budgets))):
        return None
    episode_sets = {
        frozenset((record.scene_id, record.episode_id) for record in group)
        for group in groups.values()
    }
    if len(episode_sets) != 1:
        return None
    return msp([by_budget[budget].sr for budget in budgets])


def format_table(rows: Mapping[str, MetricSummary]) -> str:
    """A Markdown table, one row per summary, numbers to 2 decimals, radii in a footnote."""
    if not rows:
        raise ConfigError("format_table needs at least one row")
    radii = {(row.success_radius, row.os_radius, row.stop_radius) for row in rows.values()}
    if len(radii) != 1:
        raise ConfigError(
            "rows were computed with different radii (success, OS, stop): "
            f"{sorted(radii)}; summarize them with the same radii to share one table"
        )
    failure_classes = FAILURE_CLASSES[1:]
    header = ["name", "n", "SR", "SPL", "OS", "NE", "NE unreachable"]
    header += [f"{CLASS_ABBREVIATIONS[name]} %" for name in failure_classes]
    lines = [_table_row(header), _table_row(["---"] * len(header))]
    for name, row in rows.items():
        cells = [name, str(row.n), f"{row.sr:.2f}", f"{row.spl:.2f}", f"{row.os:.2f}"]
        cells += ["n/a" if math.isnan(row.ne) else f"{row.ne:.2f}", str(row.ne_unreachable)]
        cells += [f"{row.class_percent(failure):.2f}" for failure in failure_classes]
        lines.append(_table_row(cells))
    success_radius, os_radius, stop_radius = radii.pop()
    lines.append("")
    lines.append(
        f"SR, SPL, OS and failure shares in %, NE in m. Success radius {success_radius:.2f} m, "
        f"OS radius {os_radius:.2f} m, stop-failure radius {stop_radius:.2f} m."
    )
    return "\n".join(lines)


def _table_row(cells: Sequence[str]) -> str:
    return "| " + " | ".join(cells) + " |"
