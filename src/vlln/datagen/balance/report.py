"""The balancing report: ``report.md`` and ``histograms.png``, the scene and category counts
before and after, with how flat each is (Gini coefficient, max / mean)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from vlln.datagen.balance.select import Selection, flatness
from vlln.eval.document import Block, Heading, Image, Paragraph, Table, to_markdown
from vlln.files import write_text_atomic

REPORT_MD = "report.md"
HISTOGRAMS_PNG = "histograms.png"
_BEFORE, _AFTER, _CAP = "#c7c7c7", "#1f77b4", "#d62728"
_MAX_LABELS = 40  # more bars than this are drawn without names


def write_report(selection: Selection, out: Path, source: Path) -> list[Path]:
    """Write the report of ``selection`` (made from ``source``) into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    png, md = out / HISTOGRAMS_PNG, out / REPORT_MD
    plot_histograms(selection, png)
    write_text_atomic(md, to_markdown(report_blocks(selection, source)))
    return [md, png]


def report_blocks(selection: Selection, source: Path) -> list[Block]:
    before = sum(selection.scenes_before.values())
    rows = []
    for name, counts_before, counts_after, cap in (
        ("scenes", selection.scenes_before, selection.scenes_after, selection.per_scene),
        (
            "categories",
            selection.categories_before,
            selection.categories_after,
            selection.per_category,
        ),
    ):
        b, a = flatness(counts_before), flatness(counts_after)
        rows.append(
            [
                name,
                str(len(counts_before)),
                str(cap),
                f"{b.gini:.3f} → {a.gini:.3f}",
                f"{b.max_over_mean:.2f} → {a.max_over_mean:.2f}",
            ]
        )
    return [
        Heading(1, f"Balanced dataset from {source}"),
        Paragraph(
            f"Kept {len(selection.kept)} of {before} trajectories: at most {selection.per_scene} "
            f"per scene and {selection.per_category} per target category, the categories "
            "taking turns, rarest first (vlln.datagen.balance.select). The paper balances its "
            "41,891 IIGN trajectories by scene and category down to 11,661."
        ),
        Table(
            ["counted by", "bins", "cap", "Gini before → after", "max/mean before → after"], rows
        ),
        Paragraph("Gini 0 and max/mean 1 mean every bin holds the same count."),
        Image(HISTOGRAMS_PNG, "scene and category counts before and after balancing"),
    ]


def plot_histograms(selection: Selection, path: Path) -> None:
    """Two panels, scenes and categories: bars of the counts before (grey) and after (blue),
    sorted by the count before, with the cap as a dashed line."""
    figure = Figure(figsize=(13.0, 8.0), dpi=100, layout="constrained")
    top, bottom = figure.subplots(2, 1)
    _panel(top, "scene", selection.scenes_before, selection.scenes_after, selection.per_scene)
    _panel(
        bottom,
        "target category",
        selection.categories_before,
        selection.categories_after,
        selection.per_category,
    )
    figure.savefig(path)


def _panel(axes: Axes, what: str, before: dict[str, int], after: dict[str, int], cap: int) -> None:
    names = sorted(before, key=lambda name: (-before[name], name))
    x = np.arange(len(names))
    axes.bar(x, [before[n] for n in names], color=_BEFORE, label="before")
    axes.bar(x, [after[n] for n in names], width=0.55, color=_AFTER, label="after")
    axes.axhline(cap, color=_CAP, linestyle="--", linewidth=1.2, label=f"cap {cap}")
    b, a = flatness(before), flatness(after)
    axes.set_title(
        f"Trajectories per {what}: {sum(before.values())} → {sum(after.values())}; "
        f"Gini {b.gini:.2f} → {a.gini:.2f}, max/mean {b.max_over_mean:.2f} → "
        f"{a.max_over_mean:.2f}"
    )
    axes.set_ylabel("trajectories")
    axes.yaxis.set_major_locator(MaxNLocator(integer=True))
    if len(names) <= _MAX_LABELS:
        axes.set_xticks(x, names, rotation=60, ha="right", fontsize=8)
    else:
        axes.set_xticks([])
        axes.set_xlabel(f"{len(names)} {what}s, most frequent first")
    axes.legend(loc="upper right")
    axes.margins(x=0.01)
