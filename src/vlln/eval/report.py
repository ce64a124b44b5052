"""``vlln report``: one or more run directories as report.md and report.html with PNG figures.

Contents: the runs compared side by side in one metric table (radii stated), each named by
the ablation switches in which the runs differ, an ablation table when they differ in exactly
one (:mod:`vlln.eval.ablation`), SR against dialog
budget (when a run swept budgets), the failure taxonomy as bars, and top-down maps of sample
episodes (a scanned scene is read from the folder the run was made with, or ``scenes``).
Every number is recomputed from the episode lines (:mod:`vlln.eval.summary`), never
copied from a summary file, so a report can use other radii than the run did.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from vlln.errors import ConfigError, VllnError
from vlln.eval.ablation import ablation_section, differing_switches, switch_label
from vlln.eval.document import (
    Block,
    Heading,
    Image,
    Paragraph,
    Table,
    Video,
    to_html,
    to_markdown,
)
from vlln.eval.episode_map import draw_episode_map
from vlln.eval.figures import plot_failure_taxonomy, plot_sr_by_budget
from vlln.eval.health import RunHealth, run_health
from vlln.eval.options import ReportOptions
from vlln.eval.pairings import people_section
from vlln.eval.results import RunDirectory, load_runs
from vlln.eval.summary import GroupSummary, budget_table, failed_actions_line, summarize_run
from vlln.files import check_output_folder, replace_folder, write_text_atomic
from vlln.tasks.aggregate import BudgetSweep, MetricSummary, format_table
from vlln.tasks.metrics import SUCCESS_RADIUS
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import scene_house
from vlln.tasks.taxonomy import CLASS_ABBREVIATIONS, SUCCESS, classify
from vlln.world.model import House

REPORT_MD = "report.md"
REPORT_HTML = "report.html"
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


@dataclass(frozen=True)
class ReportRun:
    """One run directory in a report: its label, records and summaries."""

    label: str
    path: Path
    records: list[EpisodeRecord]
    groups: list[GroupSummary]
    health: RunHealth
    scenes: str | None = None  # folder of the scanned scenes its episodes name


def write_report(
    run_dirs: Sequence[Path], out: Path, options: ReportOptions | None = None
) -> list[Path]:
    """Write report.md, report.html and their PNGs into ``out``, replacing an earlier report
    there (:func:`vlln.files.replace_folder`); returns the files written. ``options`` (none:
    the defaults) say how many episode maps and videos (MP4, PyAV needed) each run gets, the
    radii, and the folder of scanned scenes (none: each run's own ``--scenes``)."""
    options = options or ReportOptions()
    success_radius, os_radius, scenes = options.success_radius, options.os_radius, options.scenes
    if not run_dirs:
        raise ConfigError("give at least one run directory to report on")
    check_output_folder(out)
    labels = _labels(run_dirs)
    configs = [RunDirectory(path).stored_config() if path.is_dir() else None for path in run_dirs]
    switches = differing_switches(configs)
    runs = []
    for label, path, config in zip(labels, run_dirs, configs, strict=True):
        contents = load_runs([path])
        records = contents.records
        groups = summarize_run(records, success_radius, os_radius)
        where = str(scenes) if scenes is not None else RunDirectory(path).stored_scenes()
        named = switch_label(config, switches)
        label = f"{label} ({named})" if named else label
        runs.append(ReportRun(label, path, records, groups, run_health(contents), where))
    ablated = switches[0] if len(switches) == 1 else None

    def write(folder: Path) -> list[Path]:
        return _write_report(
            runs, folder, options.samples, success_radius, os_radius, options.videos, ablated
        )

    written = replace_folder(out, write, _is_report_file)
    return [out / path.name for path in written]


def _is_report_file(path: Path) -> bool:
    return path.is_file() and path.suffix in (".md", ".html", ".png", ".mp4")


def _write_report(
    runs: Sequence[ReportRun],
    out: Path,
    samples_per_run: int,
    success_radius: float,
    os_radius: float,
    videos_per_run: int,
    ablated: str | None = None,
) -> list[Path]:
    written: list[Path] = []
    blocks: list[Block] = [Heading(1, "Evaluation report")]
    blocks += _runs_section(runs)
    blocks += _metrics_section(runs, success_radius, os_radius)
    if ablated is not None:
        blocks += ablation_section(ablated, [(run.label, run.groups) for run in runs])
    blocks += _budget_section(runs, out, written)
    blocks += _taxonomy_section(runs, out, written)
    every_record = [record for run in runs for record in run.records]
    blocks += people_section(every_record, success_radius, os_radius)
    blocks += _samples_section(runs, out, written, samples_per_run, success_radius)
    blocks += _videos_section(runs, out, written, videos_per_run)
    for name, text in (
        (REPORT_MD, to_markdown(blocks)),
        (REPORT_HTML, to_html(blocks, "vlln report")),
    ):
        write_text_atomic(out / name, text)
        written.append(out / name)
    return written


def _labels(run_dirs: Sequence[Path]) -> list[str]:
    """Directory names, or full paths when two runs share a name; a row adds the switches
    in which the runs differ (:mod:`vlln.eval.ablation`)."""
    names = [path.name or str(path) for path in run_dirs]
    return names if len(set(names)) == len(names) else [str(path) for path in run_dirs]


def _row_label(run: ReportRun, group: GroupSummary, budget: int, runs: int) -> str:
    what = f"{group.agent_label} {group.task.upper()} budget {budget}"
    return what if runs == 1 else f"{run.label}: {what}"


def _runs_section(runs: Sequence[ReportRun]) -> list[Block]:
    rows = []
    for run in runs:
        config = RunDirectory(run.path).stored_config() if run.path.is_dir() else None
        source = "?" if config is None else (config.episode_file or f"split {config.split}")
        budgets = sorted({record.budget for record in run.records})
        agents = ", ".join(sorted({g.label for g in run.groups}))
        rows.append(
            [run.label, str(run.path), agents, source, str(len(run.records)), _ranges(budgets)]
        )
    header = ["run", "directory", "agent on task", "episodes from", "episode lines", "budgets"]
    return [Heading(2, "Runs"), Table(header, rows), *_health_section(runs)]


def _health_section(runs: Sequence[ReportRun]) -> list[Block]:
    """Whether each run is complete, what was skipped and what failed, per kind."""
    blocks: list[Block] = [Heading(2, "Run health")]
    blocks += [Paragraph(f"{run.label}: {run.health.line()}") for run in runs]
    kinds = sorted({kind for run in runs for kind in run.health.failures})
    skipped = sorted({kind for run in runs for kind in run.health.skipped})
    header = [
        "run", "finished", "planned", "refused", *[f"skipped: {k}" for k in skipped], *kinds
    ]  # fmt: skip
    rows = [
        [
            run.label,
            str(run.health.finished),
            "?" if run.health.planned is None else str(run.health.planned),
            str(run.health.refused),
            *[str(run.health.skipped.get(kind, 0)) for kind in skipped],
            *[str(run.health.failures.get(kind, 0)) for kind in kinds],
        ]
        for run in runs
    ]
    return [*blocks, Table(header, rows)]


def _ranges(values: list[int]) -> str:
    if len(values) > 1 and values == list(range(values[0], values[-1] + 1)):
        return f"{values[0]}-{values[-1]}"
    return ", ".join(str(value) for value in values)


def _metrics_section(
    runs: Sequence[ReportRun], success_radius: float, os_radius: float
) -> list[Block]:
    rows: dict[str, MetricSummary] = {}
    for run in runs:
        for group in run.groups:
            for budget, summary in group.sweep.by_budget.items():
                rows[_row_label(run, group, budget, len(runs))] = summary
    table, notes = Table.from_markdown(format_table(rows))
    failed = [
        f"{_row_label(run, group, budget, len(runs))}: {failed_actions_line(counts)}"
        for run in runs
        for group in run.groups
        for budget, counts in group.failed_actions.items()
        if counts
    ]
    if failed:
        notes.append(
            "Failed actions (parse: unreadable model output; server: no reply after retries; "
            "goal: a pixel showing no reachable floor), each a wasted step: "
            + "; ".join(failed)
            + "."
        )
    return [
        Heading(2, "Metrics"),
        Paragraph(
            f"Success: STOP closer than {success_radius:.2f} m (geodesic) to a goal view point. "
            f"OS (oracle success) counts an episode whose agent was ever within "
            f"{os_radius:.2f} m of a view point, the reference evaluator's radius, which is why "
            "OS is far above SR. NE is averaged over reachable final positions; unreachable "
            "ones are counted, not averaged."
        ),
        table,
        *(Paragraph(note) for note in notes),
    ]


def _budget_section(runs: Sequence[ReportRun], out: Path, written: list[Path]) -> list[Block]:
    sweeps: dict[str, BudgetSweep] = {}
    for run in runs:
        for group in run.groups:
            if len(group.sweep.by_budget) > 1:
                name = group.label if len(runs) == 1 else f"{run.label}: {group.label}"
                sweeps[name] = group.sweep
    if not sweeps:
        return []
    path = out / "sr_by_budget.png"
    plot_sr_by_budget(sweeps, path)
    written.append(path)
    blocks: list[Block] = [
        Heading(2, "Success rate against dialog budget"),
        Image(path.name, "Success rate (%) against the number of answered questions"),
    ]
    for name, sweep in sweeps.items():
        table, notes = Table.from_markdown("\n".join(budget_table(sweep)))
        blocks += [Heading(3, name), table, *(Paragraph(note) for note in notes)]
    return blocks


def _taxonomy_section(runs: Sequence[ReportRun], out: Path, written: list[Path]) -> list[Block]:
    rows: dict[str, MetricSummary] = {}
    for run in runs:
        for group in run.groups:
            budgets = sorted(group.sweep.by_budget)
            shown = {budgets[0], budgets[-1]} if budgets[0] == 0 else {budgets[-1]}
            for budget in sorted(shown):
                rows[_row_label(run, group, budget, len(runs))] = group.sweep.by_budget[budget]
    path = out / "failure_taxonomy.png"
    plot_failure_taxonomy(rows, path)
    written.append(path)
    names = ", ".join(
        f"{abbr} = {name.replace('_', ' ')}" for name, abbr in CLASS_ABBREVIATIONS.items()
    )
    return [
        Heading(2, "Failure taxonomy"),
        Paragraph(f"Every episode is a success or exactly one failure class ({names})."),
        Image(path.name, "Share of episodes per outcome class"),
    ]


def _samples_section(
    runs: Sequence[ReportRun], out: Path, written: list[Path], per_run: int, success_radius: float
) -> list[Block]:
    if per_run <= 0:
        return []
    blocks: list[Block] = [
        Heading(2, "Sample episodes"),
        Paragraph(
            "Top-down maps (x right, -z up): trajectory in blue from the start (green dot) to "
            "the end (black cross); the target in red, same-category distractors outlined in "
            "orange, the object the agent stopped at in black, questions as diamonds (Q1, Q2, "
            "...; grey when refused)."
        ),
    ]
    houses: dict[str, House] = {}
    for run_index, run in enumerate(runs):
        for record in pick_samples(run.records, per_run, success_radius):
            house = _house(record.scene_id, run.scenes, houses)
            if house is None:
                blocks.append(Paragraph(f"{record.episode_id}: scene {record.scene_id} has no map"))
                continue
            outcome = classify(record, success_radius)
            title = (
                f"{run.label}: {record.episode_id} ({record.object_category}), "
                f"{outcome.replace('_', ' ')}, {record.steps} steps, "
                f"questions: {len(record.dialog)}, budget {record.budget}"
            )
            name = _UNSAFE.sub("_", f"map_{run_index}_{record.episode_id}_b{record.budget}.png")
            draw_episode_map(record, house, out / name, title, outcome != SUCCESS)
            written.append(out / name)
            blocks += [Heading(3, title), Image(name, title)]
    return blocks


def _videos_section(
    runs: Sequence[ReportRun], out: Path, written: list[Path], per_run: int
) -> list[Block]:
    """Videos of the episodes with the most dialog (:mod:`vlln.eval.videos`)."""
    from vlln.eval.videos import dialog_first, replayable, write_videos

    if per_run <= 0:
        return []
    blocks: list[Block] = [
        Heading(2, "Episode videos"),
        Paragraph(
            "First-person view beside the map (trail in blue, agent in red, target in red); "
            "each question and its answer are captioned where they are asked."
        ),
    ]
    for run_index, run in enumerate(runs):
        chosen = dialog_first([r for r in run.records if replayable(r, run.scenes)], per_run)
        videos = write_videos(chosen, out, prefix=f"video_{run_index}", scenes=run.scenes)
        for record, (path, seconds) in zip(chosen, videos, strict=True):
            written.append(path)
            caption = (
                f"{run.label}: {record.episode_id} ({record.object_category}), budget "
                f"{record.budget}, {len(record.dialog)} questions, {seconds:.1f} s"
            )
            blocks.append(Video(path.name, caption))
    return blocks


def pick_samples(
    records: Sequence[EpisodeRecord], count: int, success_radius: float = SUCCESS_RADIUS
) -> list[EpisodeRecord]:
    """Up to ``count`` episodes at the largest budget: half successes, half failures of as
    many different classes as possible, in canonical order (deterministic)."""
    if not records:
        return []
    largest = max(record.budget for record in records)
    pool = sorted(
        (r for r in records if r.budget == largest), key=lambda r: (r.scene_id, r.episode_id)
    )
    outcomes = [classify(record, success_radius) for record in pool]
    successes = [r for r, outcome in zip(pool, outcomes, strict=True) if outcome == SUCCESS]
    first_of_class: list[int] = []
    seen: set[str] = {SUCCESS}
    for index, outcome in enumerate(outcomes):  # one of each failure class first, then the rest
        if outcome not in seen:
            seen.add(outcome)
            first_of_class.append(index)
    rest = [i for i, o in enumerate(outcomes) if o != SUCCESS and i not in first_of_class]
    failures = [pool[i] for i in first_of_class + rest]
    wanted_successes = min(len(successes), max(count // 2, count - len(failures)))
    chosen = successes[:wanted_successes] + failures[: count - wanted_successes]
    return chosen[:count]


def _house(scene_id: str, scenes: str | None, cache: dict[str, House]) -> House | None:
    """The house of a scene (procedural, or a scan in ``scenes``); None when it cannot be
    rebuilt here (no scenes folder, or one without the scene)."""
    if scene_id not in cache:
        try:
            cache[scene_id] = scene_house(scene_id, scenes)
        except VllnError:
            return None
    return cache[scene_id]
