from __future__ import annotations

import json
import shutil
import statistics
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow.parquet as pq
import pytest

from tests.datagen.stats.conftest import KEPT, REJECTED, Dataset
from vlln.datagen.stats.compute import IntDistribution, dataset_stats
from vlln.errors import DataFormatError


def _rows(house: Path) -> list[dict[str, Any]]:
    lines = (house / "meta" / "episodes.jsonl").read_text(encoding="utf-8").splitlines()
    return [json.loads(line) for line in lines]


def _walked(parquet: Path) -> float:
    """Metres walked, from the level camera poses stored per frame (z-up world: x, y on the
    floor plane)."""
    poses = np.asarray(pq.read_table(parquet).column("pose.125cm_0deg").to_pylist())
    return float(np.linalg.norm(np.diff(poses[:, :2, 3], axis=0), axis=1).sum())


@pytest.mark.slow
def test_counts_agree_with_a_recount_of_the_files(dataset: Dataset) -> None:
    house = dataset.root / "trajectories" / dataset.finished
    stats = dataset_stats(dataset.root)
    parquets = sorted((house / "data").rglob("*.parquet"))
    frames_per_trajectory = [pq.read_metadata(p).num_rows for p in parquets]
    assert stats.kept == len(parquets) == len(KEPT)
    assert stats.frames == sum(frames_per_trajectory)
    assert stats.steps.counts == dict(Counter(frames_per_trajectory))
    walked = [_walked(p) for p in parquets]
    assert stats.path_length_mean == pytest.approx(statistics.fmean(walked), abs=1e-3)
    assert stats.path_length_median == pytest.approx(statistics.median(walked), abs=1e-3)

    dialogs = [row["dialogs"] for row in _rows(house)]
    questions = [d for rows in dialogs for d in rows if d["role"] == "navigator"]
    answers = [d for rows in dialogs for d in rows if d["role"] == "oracle"]
    assert stats.turns == len(questions) == sum(len(d) for _, d in KEPT)
    assert stats.dialog_turns.counts == dict(Counter(len(rows) // 2 for rows in dialogs))
    assert stats.dialog_turns.mean == pytest.approx(len(questions) / len(dialogs))
    assert sorted(stats.question_words.values()) == sorted(
        len(q["message"].split()) for q in questions
    )
    assert sorted(stats.answer_words.values()) == sorted(len(a["message"].split()) for a in answers)
    assert stats.question_types == dict(Counter(a["question_type"] for a in answers))
    assert stats.triggers == dict(Counter(q["trigger"] for q in questions))
    assert stats.trigger_question_types["route"] == {"route": 1}
    categories = Counter(row["target"]["category"] for row in _rows(house))
    assert stats.target_categories == dict(categories)
    assert list(stats.target_categories.values()) == sorted(categories.values(), reverse=True)
    assert stats.episodes_per_house == {dataset.finished: len(KEPT)}


def test_yield_and_rejections_match_info(dataset: Dataset) -> None:
    info_path = dataset.root / "trajectories" / dataset.finished / "meta" / "info.json"
    info = json.loads(info_path.read_text(encoding="utf-8"))
    stats = dataset_stats(dataset.root)
    assert stats.houses == 1
    assert stats.attempted == info["attempted"] == len(KEPT) + len(REJECTED)
    assert stats.kept == info["total_episodes"]
    assert stats.frames == info["total_frames"]
    assert stats.rejections == info["rejections"] == dict(Counter(REJECTED))
    assert stats.yield_rate == pytest.approx(len(KEPT) / (len(KEPT) + len(REJECTED)))
    shares = stats.rejection_shares()
    assert shares["collision"] == pytest.approx(2 / 6)
    assert len(KEPT) / 6 + sum(shares.values()) == pytest.approx(1.0)
    assert list(stats.rejections) == ["collision", "target_not_in_final_view"]  # most first


def test_unfinished_houses_are_reported_in_progress_and_not_counted(dataset: Dataset) -> None:
    stats = dataset_stats(dataset.root)
    assert [(h.house, h.attempted, h.kept) for h in stats.in_progress] == [
        (dataset.unfinished, 2, 1)
    ]
    assert dataset.unfinished not in stats.episodes_per_house


def test_a_torn_journal_line_is_skipped_and_left_alone(dataset: Dataset, tmp_path: Path) -> None:
    house = tmp_path / "trajectories" / dataset.unfinished
    shutil.copytree(dataset.root / "trajectories" / dataset.unfinished / "meta", house / "meta")
    journal = house / "meta" / "journal.jsonl"
    torn = journal.read_text(encoding="utf-8") + '{"episode_id": "0_1'
    journal.write_text(torn, encoding="utf-8")
    stats = dataset_stats(tmp_path)
    assert (stats.houses, stats.in_progress[0].attempted) == (0, 2)
    assert stats.yield_rate is None and stats.steps.mean is None
    assert journal.read_text(encoding="utf-8") == torn


def test_episode_stage_is_read_from_the_split_statistics(dataset: Dataset) -> None:
    document = json.loads((dataset.root / "episodes" / "train_stats.json").read_text())
    (stage,) = dataset_stats(dataset.root).episode_stage
    totals = document["totals"]
    assert stage.split == "train"
    assert (stage.houses, stage.episodes) == (totals["houses"], totals["episodes"])
    assert sum(stage.episodes_per_house.values()) == stage.episodes
    assert sum(stage.episodes_per_category.values()) == stage.episodes
    assert sum(stage.distractors_per_target.values()) == stage.targets_used
    assert stage.skipped == totals["skipped"]
    assert dataset.finished in stage.episodes_per_house


def test_missing_or_empty_folders_are_clear_errors(tmp_path: Path) -> None:
    with pytest.raises(DataFormatError, match="not a folder"):
        dataset_stats(tmp_path / "absent")
    with pytest.raises(DataFormatError, match="no house folders"):
        dataset_stats(tmp_path)
    (tmp_path / "trajectories").mkdir()
    with pytest.raises(DataFormatError, match="no house folders"):
        dataset_stats(tmp_path)


def _copy_finished(dataset: Dataset, tmp_path: Path) -> Path:
    meta = tmp_path / "trajectories" / dataset.finished / "meta"
    shutil.copytree(dataset.root / "trajectories" / dataset.finished / "meta", meta)
    return meta


def test_info_that_disagrees_with_the_episodes_is_refused(dataset: Dataset, tmp_path: Path) -> None:
    meta = _copy_finished(dataset, tmp_path)
    info = json.loads((meta / "info.json").read_text(encoding="utf-8"))
    info["attempted"] += 1
    (meta / "info.json").write_text(json.dumps(info), encoding="utf-8")
    with pytest.raises(DataFormatError, match="do not match"):
        dataset_stats(tmp_path)


def test_unpaired_dialog_rows_are_refused(dataset: Dataset, tmp_path: Path) -> None:
    meta = _copy_finished(dataset, tmp_path)
    rows = _rows(meta.parent)
    dialogs = rows[-1]["dialogs"]
    for damaged, message in (
        (dialogs[:2] + dialogs[3:], "not question-answer pairs"),
        (dialogs[1::-1] + dialogs[2:], "must alternate navigator, oracle"),
    ):
        rows[-1]["dialogs"] = damaged
        text = "".join(json.dumps(row) + "\n" for row in rows)
        (meta / "episodes.jsonl").write_text(text, encoding="utf-8")
        with pytest.raises(DataFormatError, match=message):
            dataset_stats(tmp_path)


def test_int_distribution_summaries() -> None:
    dist = IntDistribution.of([3, 1, 3, 2])
    assert dist.counts == {1: 1, 2: 1, 3: 2}
    assert dist.values() == [1, 2, 3, 3]
    assert (dist.total, dist.mean, dist.median) == (4, 2.25, 2.5)
    assert dist.to_json()["counts"] == {"1": 1, "2": 1, "3": 2}
    empty = IntDistribution.of([])
    assert (empty.mean, empty.median, empty.to_json()["min"]) == (None, None, None)
