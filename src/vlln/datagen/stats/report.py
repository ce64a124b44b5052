"""``vlln data stats``: stats.json, stats.md and stats.png of a built dataset.

The Markdown puts the headline numbers next to the paper's (docs/reference-facts.md §5) so a
build can be judged at a glance: yield and why trajectories were dropped, the question-type
mix, dialog turns per trajectory and path length.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path

from vlln.datagen.stats.compute import DatasetStats, dataset_stats
from vlln.datagen.stats.episodes import EpisodeStageStats
from vlln.datagen.stats.figure import PAPER_TURNS_PER_TRAJECTORY, plot_dataset_stats
from vlln.eval.document import Block, Heading, Image, Paragraph, Table, to_markdown
from vlln.files import write_text_atomic, writing

STATS_JSON = "stats.json"
STATS_MD = "stats.md"
STATS_PNG = "stats.png"
PAPER_MEAN_PATH_LENGTH_M = 22.5  # docs/reference-facts.md §5
PAPER_TRAJECTORIES = 41_891
PAPER_DIALOG_TURNS = 95_559
_MD_CATEGORIES = 15


def write_stats(root: str | Path, out_dir: str | Path | None = None) -> list[Path]:
    """Write stats.json, stats.png and stats.md of the dataset at ``root`` into ``out_dir``
    (default ``<root>/stats``); returns the paths written."""
    stats = dataset_stats(root)
    out = Path(out_dir) if out_dir is not None else Path(root) / "stats"
    with writing(out):
        out.mkdir(parents=True, exist_ok=True)
    json_path, png_path, md_path = out / STATS_JSON, out / STATS_PNG, out / STATS_MD
    write_text_atomic(json_path, json.dumps(stats.to_json(), indent=2) + "\n")
    plot_dataset_stats(stats, png_path)
    write_text_atomic(md_path, to_markdown(stats_blocks(stats, STATS_PNG)))
    return [json_path, png_path, md_path]


def stats_blocks(stats: DatasetStats, figure_file: str) -> list[Block]:
    """The report as document blocks (headline table, breakdowns, figure)."""
    blocks: list[Block] = [Heading(1, f"Dataset statistics: {stats.root}")]
    if stats.in_progress:
        names = ", ".join(f"{h.house} ({h.kept}/{h.attempted} kept)" for h in stats.in_progress)
        blocks.append(Paragraph(f"In progress, not counted below: {names}."))
    blocks += [Table(["", "this dataset", "paper"], _headline_rows(stats))]
    blocks += [Heading(2, "Attempts by outcome"), _share_table("outcome", _outcomes(stats))]
    blocks += [
        Heading(2, "Dialog turns by question type"),
        _share_table("question type (oracle)", stats.question_types),
        Paragraph("By trigger (why the collector asked) and question type (oracle's class):"),
        _trigger_table(stats),
    ]
    top = dict(list(stats.target_categories.items())[:_MD_CATEGORIES])
    title = f"Target categories (top {len(top)} of {len(stats.target_categories)})"
    blocks += [Heading(2, title), _share_table("category", top, stats.kept)]
    blocks += _episode_stage_blocks(stats.episode_stage)
    blocks += [Heading(2, "Figure"), Image(figure_file, "dataset statistics")]
    return blocks


def _headline_rows(stats: DatasetStats) -> list[list[str]]:
    paper_turns = f"≈ {PAPER_TURNS_PER_TRAJECTORY}"
    return [
        ["houses (finished)", str(stats.houses), "61 train scenes"],
        ["trajectories attempted", str(stats.attempted), "–"],
        ["trajectories kept", str(stats.kept), f"{PAPER_TRAJECTORIES:,}"],
        ["yield (kept / attempted)", _percent(stats.yield_rate), "–"],
        ["frames", str(stats.frames), "–"],
        ["mean steps per trajectory", _number(stats.steps.mean, 1), "–"],
        ["mean dialog turns per trajectory", _number(stats.dialog_turns.mean, 2), paper_turns],
        ["dialog turns", str(stats.turns), f"{PAPER_DIALOG_TURNS:,}"],
        ["mean path length (m)", _number(stats.path_length_mean, 1), str(PAPER_MEAN_PATH_LENGTH_M)],
        ["median path length (m)", _number(stats.path_length_median, 1), "–"],
        ["mean words per question", _number(stats.question_words.mean, 1), "–"],
        ["mean words per answer", _number(stats.answer_words.mean, 1), "–"],
    ]


def _outcomes(stats: DatasetStats) -> dict[str, int]:
    return {"kept": stats.kept, **{f"rejected: {r}": n for r, n in stats.rejections.items()}}


def _share_table(name: str, counts: Mapping[str, int], total: int | None = None) -> Table:
    whole = sum(counts.values()) if total is None else total
    rows = [[key, str(n), _percent(n / whole if whole else None)] for key, n in counts.items()]
    return Table([name, "count", "share"], rows or [["(none)", "0", "–"]])


def _trigger_table(stats: DatasetStats) -> Table:
    kinds = list(stats.question_types)
    rows = [
        [trigger, *(str(by_kind.get(kind, 0)) for kind in kinds)]
        for trigger, by_kind in stats.trigger_question_types.items()
    ]
    return Table(["trigger", *kinds], rows or [["(none)"]])


def _episode_stage_blocks(stages: list[EpisodeStageStats]) -> list[Block]:
    blocks: list[Block] = []
    for stage in stages:
        per_house = stage.episodes_per_house.values()
        house_range = f"{min(per_house, default=0)}–{max(per_house, default=0)}"
        rows = [
            ["houses", str(stage.houses)],
            ["instances", str(stage.instances)],
            ["targets with episodes", str(stage.targets_used)],
            ["episodes per task", str(stage.episodes)],
            ["episodes per house (min–max)", house_range],
            ["target categories", str(len(stage.episodes_per_category))],
            ["mean distractors per target", _number(stage.mean_distractors, 2)],
            ["mean start distance (m)", _number(stage.mean_start_distance, 1)],
            *([f"skipped: {r}", str(n)] for r, n in stage.skipped.items()),
        ]
        blocks += [Heading(2, f"Episodes ({stage.split} split)"), Table(["", "value"], rows)]
    return blocks


def _percent(share: float | None) -> str:
    return "–" if share is None else f"{100.0 * share:.1f}%"


def _number(value: float | None, digits: int) -> str:
    return "–" if value is None else f"{value:.{digits}f}"
