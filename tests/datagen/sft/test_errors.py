"""What export_sft says about inputs it cannot use."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest
from tests.datagen.sft.conftest import HandDataset

from vlln.datagen.sft import SftConfig, export_sft
from vlln.errors import ConfigError, DataFormatError


def test_a_missing_folder_is_a_config_error(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="is not a folder"):
        export_sft(tmp_path / "missing", tmp_path / "out", progress=False)


def test_a_folder_without_trajectories_is_not_a_dataset(tmp_path: Path) -> None:
    (tmp_path / "data" / "episodes").mkdir(parents=True)
    with pytest.raises(DataFormatError, match="not a trajectory dataset"):
        export_sft(tmp_path / "data", tmp_path / "out", progress=False)
    assert not (tmp_path / "out").exists()


def test_a_dataset_named_twice_is_refused(tmp_path: Path) -> None:
    (tmp_path / "data").mkdir()
    with pytest.raises(ConfigError, match="is given more than once; name each dataset once"):
        export_sft([tmp_path / "data", tmp_path / "." / "data"], tmp_path / "out", progress=False)
    with pytest.raises(ConfigError, match="no dataset given"):
        export_sft([], tmp_path / "out", progress=False)
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_house_of_another_format_version_is_refused(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    copy = copy_dataset(hand_dataset, tmp_path)
    info = copy / "trajectories" / hand_dataset.house / "meta" / "info.json"
    info.write_text(json.dumps({"format_version": "vlln-trajectories/1.0"}), encoding="utf-8")
    with pytest.raises(DataFormatError, match="rebuild the data"):
        export_sft(copy, tmp_path / "out", progress=False)


def copy_dataset(hand_dataset: HandDataset, tmp_path: Path) -> Path:
    copy = tmp_path / "copy"
    shutil.copytree(hand_dataset.root, copy)
    return copy


def test_malformed_dialog_rows_name_the_file_and_episode(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    copy = copy_dataset(hand_dataset, tmp_path)
    episodes = copy / "trajectories" / hand_dataset.house / "meta" / "episodes.jsonl"
    rows = [json.loads(line) for line in episodes.read_text(encoding="utf-8").splitlines()]
    rows[1]["dialogs"] = rows[1]["dialogs"][1:]
    episodes.write_text("".join(json.dumps(row) + "\n" for row in rows), encoding="utf-8")
    with pytest.raises(DataFormatError, match=r"episodes.jsonl, episode 1: .*pairs"):
        export_sft(copy, tmp_path / "out", progress=False)
    del rows[1]["tasks"]
    episodes.write_text("".join(json.dumps(row) + "\n" for row in rows), encoding="utf-8")
    with pytest.raises(DataFormatError, match="episode 1: unreadable"):
        export_sft(copy, tmp_path / "out", progress=False)


def test_missing_images_and_frames_are_data_format_errors(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    copy = copy_dataset(hand_dataset, tmp_path)
    house = copy / "trajectories" / hand_dataset.house
    image = house / "videos/chunk-000/observation.images.rgb.125cm_0deg/episode_000001_1.jpg"
    kept = image.read_bytes()
    image.unlink()
    with pytest.raises(DataFormatError, match=r"episode 1: .*episode_000001_1\.jpg.*incomplete"):
        export_sft(copy, tmp_path / "out", progress=False)
    image.write_bytes(kept)
    (house / "data" / "chunk-000" / "episode_000002.parquet").unlink()
    with pytest.raises(DataFormatError, match="episode 2: unreadable"):
        export_sft(copy, tmp_path / "out", progress=False)


def test_the_output_folder_must_be_new_empty_or_an_export(
    hand_dataset: HandDataset, tmp_path: Path
) -> None:
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "notes.txt").write_text("mine", encoding="utf-8")
    with pytest.raises(ConfigError, match=r"not an export \(notes.txt\)"):
        export_sft(hand_dataset.root, busy, progress=False)
    assert (busy / "notes.txt").read_text(encoding="utf-8") == "mine"
    with pytest.raises(ConfigError, match="is not a folder"):
        export_sft(hand_dataset.root, busy / "notes.txt", progress=False)


@pytest.mark.parametrize(
    "settings",
    [
        {"seed": -1},
        {"sample_step": 0},
        {"repeats": "many"},
        {"max_answers": -1},
        {"history_frames": 2.5},
        {"max_turn_run": 5},
    ],
)
def test_invalid_settings_are_config_errors(settings: dict[str, Any]) -> None:
    with pytest.raises(ConfigError, match=f"^--{next(iter(settings)).replace('_', '-')}: "):
        SftConfig.build(settings)
