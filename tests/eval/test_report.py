"""`vlln report`: Markdown and HTML with the metric table, charts and episode maps."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from matplotlib.figure import Figure
from PIL import Image

from tests.eval.runs import evaluate
from tests.tasks.test_metrics import make_record
from vlln.cli import main
from vlln.eval.episode_map import _draw_storey, question_positions
from vlln.eval.report import pick_samples
from vlln.tasks.record import DialogTurn, EndReason
from vlln.tasks.scenes import SceneCache, procedural_scene_id


@pytest.fixture(scope="module")
def runs(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> list[Path]:
    """Two runs to compare: the expert and the random agent, both at budgets 0 and 1."""
    root = tmp_path_factory.mktemp("report_runs")
    for agent in ("expert", "random"):
        evaluate(root / agent, split_cache, scenes, agent=agent, episodes=3, max_steps=150)
    return [root / "expert", root / "random"]


@pytest.mark.slow
def test_report_compares_runs_with_table_charts_and_maps(
    runs: list[Path], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "report"
    args = ["report", *map(str, runs), "--out", str(out), "--samples", "2"]
    assert main(args) == 0
    markdown = (out / "report.md").read_text()
    page = (out / "report.html").read_text()
    assert "| name | n | SR | SPL | OS | NE |" in markdown
    for row in ("expert: expert IIGN budget 0", "random: random IIGN budget 1"):
        assert row in markdown and row in page
    assert "OS radius 3.00 m" in markdown and "within 3.00 m" in page
    images = re.findall(r"!\[[^]]*\]\(([^)]+)\)", markdown)
    assert "sr_by_budget.png" in images and "failure_taxonomy.png" in images
    maps = [name for name in images if name.startswith("map_")]
    assert len(maps) == 4  # two per run
    for name in images:
        assert f'src="{name}"' in page
        with Image.open(out / name) as picture:
            assert picture.format == "PNG" and min(picture.size) > 200
            assert len(picture.getcolors(1 << 20) or []) > 20  # drawn, not blank


def test_one_run_report_defaults_next_to_the_run(runs: list[Path]) -> None:
    assert main(["report", str(runs[0]), "--samples", "1"]) == 0
    assert (runs[0] / "report" / "report.html").exists()


def test_samples_mix_successes_and_distinct_failures() -> None:
    success = make_record(episode_id="s1")
    stop_failure = make_record(episode_id="f1", geodesic_trace=[2.0, 0.5])
    wrong = make_record(
        episode_id="f2", geodesic_trace=[5.0], stop_instance_id=3, stop_instance_category="sofa"
    )
    wrong_again = make_record(
        episode_id="f3", geodesic_trace=[5.0], stop_instance_id=3, stop_instance_category="sofa"
    )
    chosen = pick_samples([wrong_again, success, stop_failure, wrong], 3)
    assert [r.episode_id for r in chosen] == ["s1", "f1", "f2"]
    assert pick_samples([success], 4) == [success]
    assert pick_samples([], 4) == []


def test_question_positions_follow_the_movement_actions() -> None:
    record = make_record(
        positions=[[0.0, 0.0, 0.0], [0.0, -0.25, 0.0], [0.0, -0.25, 0.5]],
        actions=["TALK", "MOVE_FORWARD", "LOOK_DOWN", "TALK", "TURN_LEFT", "STOP"],
        dialog=[DialogTurn(0, "q", "a", "route", True), DialogTurn(1, "q", "a", "route", True)],
        end_reason=EndReason.STOP.value,
    )
    assert question_positions(record) == [(0.0, 0.0), (0.0, -0.25)]


def test_rows_and_scores_name_the_detector(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    dirs = []
    for detector, stop in (("truth", 7), ("noisy", 9)):
        run = tmp_path / f"frontier-{detector}"
        run.mkdir()
        records = [
            make_record(agent="frontier", detector=detector, budget=b, stop_instance_id=stop)
            for b in (0, 1)
        ]
        (run / "episodes.jsonl").write_text(
            "".join(json.dumps(r.to_json()) + "\n" for r in records)
        )
        dirs.append(str(run))
    out = tmp_path / "report"
    assert main(["report", *dirs, "--out", str(out), "--samples", "0"]) == 0
    markdown = (out / "report.md").read_text()
    for row in (
        "frontier-truth: frontier (truth detector) IIGN budget 0",
        "frontier-noisy: frontier (noisy detector) IIGN budget 1",
    ):
        assert row in markdown
    capsys.readouterr()
    assert main(["score", *dirs]) == 0  # one episode under two detectors is not a clash
    scores = capsys.readouterr().out
    assert "## frontier (truth detector) on IIGN" in scores
    assert "## frontier (noisy detector) on IIGN" in scores


@pytest.mark.parametrize(
    ("answered", "labels"),
    [
        ([True], {"question (answered)"}),
        ([True, False], {"question (answered)", "question (refused)"}),
        ([False], {"question (refused)"}),
    ],
)
def test_the_map_legend_names_each_kind_of_question_drawn(
    scenes: SceneCache, answered: list[bool], labels: set[str]
) -> None:
    house = scenes.get(procedural_scene_id(0)).house
    target = house.instances[0]
    x, _, z = target.box.max
    record = make_record(
        object_category=target.category,
        target_ids=[target.id],
        positions=[[x, z, 0.0]],
        actions=["TALK"] * len(answered),
        dialog=[DialogTurn(0, "q", "a", "route", yes) for yes in answered],
    )
    axes = Figure().subplots()
    _draw_storey(axes, record, house, 0, None, mark_stop_object=False)
    drawn = set(axes.get_legend_handles_labels()[1])
    assert drawn & {"question (answered)", "question (refused)"} == labels
