from __future__ import annotations

import math

import numpy as np
import pytest

from tests.tasks.test_metrics import ask, make_record
from vlln.errors import ConfigError
from vlln.tasks.aggregate import (
    MetricSummary,
    format_table,
    summarize,
    summarize_budgets,
    summarize_by,
)
from vlln.tasks.record import EndReason, EpisodeRecord
from vlln.tasks.taxonomy import (
    AMBIGUOUS_DETECTION,
    EXPLORATION_FAILURE,
    FAILURE_CLASSES,
    MISSED_DETECTION,
    STOP_FAILURE,
    SUCCESS,
    WRONG_DETECTION,
)

CAP = EndReason.STEP_CAP.value


def one_of_each() -> list[EpisodeRecord]:
    """Six episodes, one per class, with known SPL, OS and NE."""
    return [
        # success: d0 4, L 5 -> SPL 0.8; NE 0.1; OS
        make_record(episode_id="s", steps=10, dialog=[ask(1), ask(2)]),
        # stop failure at 0.5 m; OS
        make_record(episode_id="st", steps=20, geodesic_trace=[2.0, 0.5]),
        # ambiguous detection at 4 m, never within 3 m; no OS
        make_record(episode_id="ad", steps=30, geodesic_trace=[5.0, 4.0], stop_instance_id=9),
        # wrong detection at an unreachable spot; NE inf
        make_record(
            episode_id="wd",
            steps=40,
            geodesic_trace=[5.0, math.inf],
            stop_instance_id=3,
            stop_instance_category="sofa",
            dialog=[ask(5)],
        ),
        # missed detection, passed within 2 m; OS
        make_record(episode_id="md", end_reason=CAP, steps=50, geodesic_trace=[2.0, 6.0]),
        # exploration failure; no OS
        make_record(
            episode_id="ex",
            end_reason=CAP,
            steps=60,
            geodesic_trace=[8.0],
            target_seen_step=None,
            dialog=[ask(1), ask(2), ask(3, answered=False)],
        ),
    ]


def test_summarize_one_of_each() -> None:
    summary = summarize(one_of_each())
    assert summary.n == 6
    assert summary.sr == pytest.approx(100.0 / 6)
    assert summary.spl == pytest.approx(100.0 * 0.8 / 6)
    assert summary.os == pytest.approx(50.0)
    assert summary.ne == pytest.approx((0.1 + 0.5 + 4.0 + 6.0 + 8.0) / 5)
    assert summary.ne_unreachable == 1
    assert summary.mean_steps == pytest.approx(35.0)
    assert summary.mean_questions == pytest.approx(1.0)
    assert summary.failures == dict.fromkeys(FAILURE_CLASSES, 1)
    assert (summary.success_radius, summary.os_radius, summary.stop_radius) == (0.25, 3.0, 1.0)
    assert summary.class_percent(MISSED_DETECTION) == pytest.approx(100.0 / 6)


def test_summarize_radii_change_results() -> None:
    records = one_of_each()
    assert summarize(records, os_radius=0.25).os == pytest.approx(100.0 / 6)
    wide = summarize(records, success_radius=0.6, stop_radius=5.0)
    assert wide.sr == pytest.approx(200.0 / 6)
    assert wide.failures[STOP_FAILURE] == 0  # the stop at 0.5 m became a success
    assert wide.failures[AMBIGUOUS_DETECTION] == 1  # facing a distractor is AD at any radius
    assert wide.success_radius == 0.6


def test_summarize_all_unreachable_reports_nan_not_zero() -> None:
    summary = summarize([make_record(geodesic_trace=[math.inf], end_reason=CAP)])
    assert math.isnan(summary.ne)
    assert summary.ne_unreachable == 1


def test_summarize_rejects_empty() -> None:
    with pytest.raises(ConfigError, match="at least one"):
        summarize([])


def test_class_percent_rejects_unknown_class() -> None:
    with pytest.raises(ConfigError, match="unknown outcome class"):
        summarize(one_of_each()).class_percent("lost")


def test_summarize_by_category() -> None:
    records = [*one_of_each(), make_record(episode_id="b1", object_category="bed")]
    records.append(
        make_record(
            episode_id="b2",
            object_category="bed",
            geodesic_trace=[7.0],
            stop_instance_id=9,
            stop_instance_category="bed",
        )
    )
    by_category = summarize_by(records)
    assert list(by_category) == ["chair", "bed"]
    assert by_category["chair"].n == 6
    assert by_category["bed"].n == 2
    assert by_category["bed"].sr == pytest.approx(50.0)
    assert by_category["bed"].failures[SUCCESS] == 1
    assert by_category["bed"].failures[WRONG_DETECTION] == 0
    assert by_category["bed"].failures[AMBIGUOUS_DETECTION] == 1  # another bed
    by_task = summarize_by(records, key=lambda record: record.task)
    assert by_task["iign"].n == 8


def sweep_records(rates: list[float], episodes: int = 500) -> list[EpisodeRecord]:
    """Records whose success rate at budget i is rates[i] percent over the same episodes."""
    records = []
    for budget, rate in enumerate(rates):
        successes = round(rate * episodes / 100.0)
        for index in range(episodes):
            trace = [1.0, 0.1] if index < successes else [1.0, 5.0]
            records.append(make_record(episode_id=str(index), budget=budget, geodesic_trace=trace))
    return records


def test_summarize_budgets_paper_sweep_gives_msp() -> None:
    rates = [19.6, 22.0, 23.0, 23.0, 25.2, 25.4]
    records = sweep_records(rates)
    np.random.default_rng(7).shuffle(records)  # order of records must not matter
    sweep = summarize_budgets(records)
    assert list(sweep.by_budget) == [0, 1, 2, 3, 4, 5]
    assert [sweep.by_budget[b].sr for b in range(6)] == pytest.approx(rates)
    assert sweep.msp is not None
    assert round(sweep.msp, 2) == 4.12


def test_summarize_budgets_without_complete_sweep_has_no_msp() -> None:
    records = [r for r in sweep_records([10.0, 20.0, 30.0], episodes=10) if r.budget != 1]
    sweep = summarize_budgets(records)
    assert list(sweep.by_budget) == [0, 2]
    assert sweep.msp is None
    assert summarize_budgets(sweep_records([10.0], episodes=10)).msp is None


def test_summarize_budgets_needs_same_episodes_for_msp() -> None:
    records = sweep_records([10.0, 20.0], episodes=10)
    records.append(make_record(episode_id="extra", budget=1))
    assert summarize_budgets(records).msp is None


def test_summarize_budgets_rejects_mixed_agents() -> None:
    records = [make_record(agent="a"), make_record(agent="b", budget=1)]
    with pytest.raises(ConfigError, match="one agent"):
        summarize_budgets(records)


def table_cells(table: str, name: str) -> list[str]:
    (line,) = [line for line in table.splitlines() if line.startswith(f"| {name} |")]
    return [cell.strip() for cell in line.strip("|").split("|")]


def test_format_table_numbers() -> None:
    rows: dict[str, MetricSummary] = {
        "all": summarize(one_of_each()),
        "paper": summarize(sweep_records([25.4], episodes=500)),
    }
    table = format_table(rows)
    header = table_cells(table, "name")
    assert header == [
        "name", "n", "SR", "SPL", "OS", "NE", "NE unreachable",
        "ST %", "AD %", "WD %", "MD %", "Expl %",
    ]  # fmt: skip
    all_row = dict(zip(header, table_cells(table, "all"), strict=True))
    assert all_row["n"] == "6"
    assert all_row["SR"] == "16.67"
    assert all_row["SPL"] == "13.33"
    assert all_row["OS"] == "50.00"
    assert all_row["NE"] == "3.72"
    assert all_row["NE unreachable"] == "1"
    for abbreviation in ("ST %", "AD %", "WD %", "MD %", "Expl %"):
        assert all_row[abbreviation] == "16.67"
    paper_row = dict(zip(header, table_cells(table, "paper"), strict=True))
    assert paper_row["SR"] == "25.40"
    assert paper_row["WD %"] == "0.00"
    assert paper_row["AD %"] == "0.00"
    assert paper_row["ST %"] == "74.60"  # failed stops facing the target 5 m away
    assert "OS radius 3.00 m" in table
    assert "Success radius 0.25 m" in table


def test_format_table_marks_missing_ne_and_counts_failures() -> None:
    rows = {"lost": summarize([make_record(end_reason=CAP, geodesic_trace=[math.inf])])}
    cells = table_cells(format_table(rows), "lost")
    assert cells[5:7] == ["n/a", "1"]
    assert cells[-2:] == ["100.00", "0.00"]  # seen (MD), not an exploration failure
    assert (
        summarize([make_record(end_reason=CAP, target_seen_step=None)]).failures[
            EXPLORATION_FAILURE
        ]
        == 1
    )


def test_format_table_rejects_mixed_radii_and_empty() -> None:
    rows = {"a": summarize(one_of_each()), "b": summarize(one_of_each(), os_radius=1.0)}
    with pytest.raises(ConfigError, match="different radii"):
        format_table(rows)
    with pytest.raises(ConfigError, match="at least one row"):
        format_table({})
