"""The dataset statistics figure, laid out like the paper's (step counts, dialog turns per
trajectory and words per turn on top; question types and target categories below), with the
filter's rejection reasons where the paper shows a word cloud, since yield is what a build
most needs to see.

Built as a :class:`matplotlib.figure.Figure` (no pyplot state), so it can be drawn without a
display and from any process.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from numpy.typing import NDArray

from vlln.datagen.stats.compute import DatasetStats, IntDistribution
from vlln.files import writing

FIGURE_SIZE = (15.0, 8.6)  # inches
FIGURE_DPI = 100
TOP_CATEGORIES = 15
PAPER_TURNS_PER_TRAJECTORY = 1.9  # docs/reference-facts.md §5
_KEPT_COLOR = "#2ca02c"
_REJECT_COLOR = "#d62728"
_QUESTION_COLOR = "#1f77b4"
_ANSWER_COLOR = "#ff7f0e"
_TYPE_COLORS = {
    "attribute": "#9467bd",
    "route": "#1f77b4",
    "disambiguation": "#ff7f0e",
    "other": "#7f7f7f",
}


def plot_dataset_stats(stats: DatasetStats, path: Path) -> None:
    """Write the six-panel statistics figure of ``stats`` to ``path`` (PNG)."""
    fig = Figure(figsize=FIGURE_SIZE)
    axes = fig.subplots(2, 3)
    _step_counts(axes[0, 0], stats.steps)
    _dialog_turns(axes[0, 1], stats.dialog_turns)
    _words_per_turn(axes[0, 2], stats.question_words, stats.answer_words)
    _question_types(axes[1, 0], stats.question_types, stats.turns)
    _target_categories(axes[1, 1], stats.target_categories)
    _outcomes(axes[1, 2], stats)
    title = (
        f"Dataset statistics: {_plural(stats.kept, 'trajectory', 'trajectories')} "
        f"from {_plural(stats.houses, 'house', 'houses')}"
    )
    if stats.in_progress:
        title += f" ({_plural(len(stats.in_progress), 'house', 'houses')} in progress)"
    fig.suptitle(title, fontsize=14)
    fig.tight_layout()
    with writing(path):
        fig.savefig(path, dpi=FIGURE_DPI)


def _step_counts(ax: Axes, steps: IntDistribution) -> None:
    ax.set_title("(a) Step count per trajectory")
    if not steps.total:
        _empty(ax, "no trajectories yet")
        return
    values = np.asarray(steps.values())
    most = min(30, max(5, 2 * math.ceil(math.sqrt(len(values)))))  # fewer bins for few
    ax.hist(values, bins=_integer_bins(values, most), color=_QUESTION_COLOR, edgecolor="white")
    ax.axvline(float(values.mean()), color="black", linestyle="--", linewidth=1.2)
    summary = f"mean {values.mean():.1f}\nmedian {np.median(values):.0f}"
    box = {"facecolor": "white", "alpha": 0.85, "edgecolor": "#cccccc"}
    ax.text(0.97, 0.95, summary, transform=ax.transAxes, ha="right", va="top", fontsize=9, bbox=box)
    ax.set_xlabel("steps (frames)")
    ax.set_ylabel("trajectories")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def _dialog_turns(ax: Axes, turns: IntDistribution) -> None:
    ax.set_title("(b) Dialog turns per trajectory")
    if not turns.total:
        _empty(ax, "no trajectories yet")
        return
    xs = np.arange(0, max(turns.counts) + 1)
    heights = [turns.counts.get(int(x), 0) for x in xs]
    bars = ax.bar(xs, heights, color=_QUESTION_COLOR)
    ax.bar_label(bars, labels=[str(h) if h else "" for h in heights], fontsize=8, padding=1)
    mean = turns.mean or 0.0
    ax.axvline(mean, color="black", linestyle="--", linewidth=1.2, label=f"mean {mean:.2f}")
    paper = f"paper ≈ {PAPER_TURNS_PER_TRAJECTORY}"
    ax.axvline(PAPER_TURNS_PER_TRAJECTORY, color="grey", linestyle=":", linewidth=1.5, label=paper)
    ax.legend(fontsize=9)
    ax.set_xlabel("question-answer turns")
    ax.set_ylabel("trajectories")
    ax.set_xticks(xs)
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.margins(y=0.12)


def _words_per_turn(ax: Axes, questions: IntDistribution, answers: IntDistribution) -> None:
    ax.set_title("(c) Words per turn")
    if not questions.total:
        _empty(ax, "no dialog turns yet")
        return
    q, a = np.asarray(questions.values()), np.asarray(answers.values())
    edges = _integer_bins(np.concatenate([q, a]), 40)
    for values, color, name in ((q, _QUESTION_COLOR, "questions"), (a, _ANSWER_COLOR, "answers")):
        label = f"{name} (mean {values.mean():.1f})"
        ax.hist(values, bins=edges, color=color, alpha=0.7, label=label)
    ax.legend(fontsize=9)
    ax.set_xlabel("words")
    ax.set_ylabel("turns")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))


def _question_types(ax: Axes, types: dict[str, int], turns: int) -> None:
    ax.set_title("(d) Question types (oracle's classification)")
    if not turns:
        _empty(ax, "no dialog turns yet")
        return
    names = list(types)
    colors = [_TYPE_COLORS.get(name, "#8c564b") for name in names]
    bars = ax.bar(names, [types[n] for n in names], color=colors)
    labels = [f"{types[n]} ({100.0 * types[n] / turns:.0f}%)" for n in names]
    ax.bar_label(bars, labels=labels, fontsize=9, padding=1)
    ax.set_ylabel("turns")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.margins(y=0.12)


def _target_categories(ax: Axes, categories: dict[str, int]) -> None:
    shown = list(categories)[:TOP_CATEGORIES]
    title = "(e) Target categories"
    if len(categories) > len(shown):
        title += f" (top {len(shown)} of {len(categories)})"
    ax.set_title(title)
    if not shown:
        _empty(ax, "no trajectories yet")
        return
    ys = np.arange(len(shown))
    bars = ax.barh(ys, [categories[name] for name in shown], color=_QUESTION_COLOR)
    ax.bar_label(bars, fontsize=8, padding=2)
    ax.set_yticks(ys, shown, fontsize=9)
    ax.set_ylim(max(len(shown), 6) - 0.5, -0.5)  # same bar height whatever the count
    ax.set_xlabel("trajectories")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.margins(x=0.12)


def _outcomes(ax: Axes, stats: DatasetStats) -> None:
    """Kept and each rejection reason as a share of the attempted trajectories."""
    ax.set_title("(f) Attempts: kept and rejected by reason")
    if not stats.attempted:
        _empty(ax, "no finished attempts yet")
        return
    names = ["kept", *(reason.replace("_", " ") for reason in stats.rejections)]
    counts = [stats.kept, *stats.rejections.values()]
    ys = np.arange(len(names))
    shares = [100.0 * n / stats.attempted for n in counts]
    colors = [_KEPT_COLOR] + [_REJECT_COLOR] * len(stats.rejections)
    bars = ax.barh(ys, shares, color=colors)
    labels = [f"{n} ({s:.0f}%)" for n, s in zip(counts, shares, strict=True)]
    ax.bar_label(bars, labels=labels, fontsize=9, padding=2)
    ax.set_yticks(ys, names, fontsize=9)
    ax.invert_yaxis()
    ax.set_xlim(0.0, 118.0)
    ax.set_xlabel(f"share of {stats.attempted} attempted trajectories (%)")


def _integer_bins(values: NDArray[np.int_], most: int) -> list[float]:
    """Bin edges at half-integers, ``most`` bins at most, so whole numbers fall mid-bin."""
    low, high = int(values.min()), int(values.max())
    width = max(1, math.ceil((high - low + 1) / most))
    return [low - 0.5 + width * k for k in range((high - low) // width + 2)]


def _plural(count: int, one: str, many: str) -> str:
    return f"{count} {one if count == 1 else many}"


def _empty(ax: Axes, message: str) -> None:
    ax.text(0.5, 0.5, message, transform=ax.transAxes, ha="center", va="center", color="grey")
    ax.set_xticks([])
    ax.set_yticks([])
