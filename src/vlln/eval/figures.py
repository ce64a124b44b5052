"""Report charts: success rate against dialog budget, and the failure taxonomy as bars.

Figures are built as :class:`matplotlib.figure.Figure` objects (no pyplot state), so reports
can be written from any thread or process without a display.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from vlln.errors import ConfigError
from vlln.files import writing
from vlln.tasks.aggregate import BudgetSweep, MetricSummary
from vlln.tasks.taxonomy import CLASS_ABBREVIATIONS, FAILURE_CLASSES

CLASS_COLORS: dict[str, str] = {
    "success": "#2ca02c",
    "stop_failure": "#bcbd22",
    "ambiguous_detection": "#ff7f0e",
    "wrong_detection": "#d62728",
    "missed_detection": "#9467bd",
    "exploration_failure": "#7f7f7f",
}


def plot_sr_by_budget(sweeps: Mapping[str, BudgetSweep], path: Path) -> None:
    """One line per sweep: SR (%) against the number of answered questions; MSP in the legend."""
    if not sweeps:
        raise ConfigError("plot_sr_by_budget needs at least one budget sweep")
    fig = Figure(figsize=(6.4, 4.0))
    ax = fig.subplots()
    for label, sweep in sweeps.items():
        budgets = list(sweep.by_budget)
        rates = [summary.sr for summary in sweep.by_budget.values()]
        name = label if sweep.msp is None else f"{label} (MSP {sweep.msp:+.2f})"
        ax.plot(budgets, rates, marker="o", linewidth=2, label=name)
    ax.set_xlabel("dialog budget (answered questions)")
    ax.set_ylabel("success rate (%)")
    ax.set_title("Success rate against dialog budget")
    ax.set_ylim(-3.0, 105.0)
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    with writing(path):
        fig.savefig(path, dpi=120)


def plot_failure_taxonomy(rows: Mapping[str, MetricSummary], path: Path) -> None:
    """Grouped bars: the share of each outcome class (success first), one bar per row."""
    if not rows:
        raise ConfigError("plot_failure_taxonomy needs at least one summary")
    fig = Figure(figsize=(7.0 if len(rows) == 1 else 10.0, 4.0))
    ax = fig.subplots()
    x = np.arange(len(FAILURE_CLASSES))
    width = 0.8 / len(rows)
    for k, (label, summary) in enumerate(rows.items()):
        shares = [summary.class_percent(name) for name in FAILURE_CLASSES]
        offsets = x - 0.4 + width * (k + 0.5)
        bars = ax.bar(offsets, shares, width, label=label)
        if len(rows) == 1:
            for bar, name in zip(bars, FAILURE_CLASSES, strict=True):
                bar.set_color(CLASS_COLORS[name])
        if len(rows) <= 2:
            ax.bar_label(bars, fmt="%.0f", fontsize=7, padding=1)
    ax.set_xticks(x, [CLASS_ABBREVIATIONS[name] for name in FAILURE_CLASSES])
    ax.set_ylabel("episodes (%)")
    ax.set_title("Outcomes: success and failure taxonomy")
    ax.set_ylim(0.0, 105.0)
    ax.grid(axis="y", alpha=0.3)
    if len(rows) > 1:
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    with writing(path):
        fig.savefig(path, dpi=120)
