from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
from PIL import Image

from tests.datagen.stats.conftest import Dataset
from vlln.datagen.stats.compute import dataset_stats
from vlln.datagen.stats.figure import FIGURE_DPI, FIGURE_SIZE
from vlln.datagen.stats.report import STATS_JSON, STATS_MD, STATS_PNG, write_stats

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
EXPECTED_SIZE = (round(FIGURE_SIZE[0] * FIGURE_DPI), round(FIGURE_SIZE[1] * FIGURE_DPI))


def _check_png(path: Path) -> None:
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    with Image.open(path) as image:
        image.verify()
    with Image.open(path) as image:
        assert image.size == EXPECTED_SIZE
        grey = np.asarray(image.convert("L"))
    assert grey.min() < 100 < grey.max()  # something dark drawn on the white page


def test_write_stats_defaults_to_a_stats_folder_in_the_dataset(
    dataset: Dataset, tmp_path: Path
) -> None:
    root = tmp_path / "copy"
    shutil.copytree(dataset.root, root)
    written = write_stats(root)
    assert written == [root / "stats" / name for name in (STATS_JSON, STATS_PNG, STATS_MD)]
    assert all(path.is_file() for path in written)


def test_stats_json_png_and_markdown(dataset: Dataset, tmp_path: Path) -> None:
    json_path, png_path, md_path = write_stats(dataset.root, tmp_path / "out")
    stats = dataset_stats(dataset.root)
    document = json.loads(json_path.read_text(encoding="utf-8"))
    assert document == json.loads(json.dumps(stats.to_json()))
    assert document["yield"] == round(stats.kept / stats.attempted, 4)
    assert document["rejections"]["collision"]["count"] == stats.rejections["collision"]
    assert document["houses_in_progress"][0]["house"] == dataset.unfinished
    _check_png(png_path)

    markdown = md_path.read_text(encoding="utf-8")
    assert f"![dataset statistics]({STATS_PNG})" in markdown
    assert f"| yield (kept / attempted) | {100 * stats.kept / stats.attempted:.1f}% |" in markdown
    assert "| rejected: collision | 2 |" in markdown
    assert f"| {stats.dialog_turns.mean:.2f} | ≈ 1.9 |" in markdown
    assert f"| {stats.path_length_mean:.1f} | 22.5 |" in markdown
    for kind, count in stats.question_types.items():
        assert f"| {kind} | {count} |" in markdown
    assert f"In progress, not counted below: {dataset.unfinished} (1/2 kept)." in markdown
    assert "## Episodes (train split)" in markdown


def test_a_dataset_with_only_houses_in_progress_still_reports(
    dataset: Dataset, tmp_path: Path
) -> None:
    house = tmp_path / "trajectories" / dataset.unfinished
    shutil.copytree(dataset.root / "trajectories" / dataset.unfinished / "meta", house / "meta")
    json_path, png_path, md_path = write_stats(tmp_path, tmp_path / "out")
    document = json.loads(json_path.read_text(encoding="utf-8"))
    assert (document["houses"], document["kept"], document["yield"]) == (0, 0, None)
    assert document["episode_stage"] == []
    _check_png(png_path)
    markdown = md_path.read_text(encoding="utf-8")
    assert "| trajectories kept | 0 |" in markdown
    assert "| yield (kept / attempted) | – |" in markdown
