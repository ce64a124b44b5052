"""Files handed back to vlln (model folders, datasets, exports, scene summaries) are untrusted
input, even those vlln wrote: a file past its cap or JSON nested past parse_json's depth is one
DataFormatError line that names the file, never a traceback or an exhausted memory."""

from __future__ import annotations

import base64
import json
import lzma
from collections.abc import Callable
from pathlib import Path

import pytest

from vlln.agents.local.card import CARD_FILE, read_card
from vlln.datagen.build import recorded_strategy
from vlln.datagen.layout import EPISODES_FILE, INFO_FILE, SETTINGS_FILE
from vlln.datagen.reader import HouseDataset
from vlln.datagen.stats.episodes import read_episode_stage
from vlln.datagen.writer import read_journal
from vlln.errors import DataFormatError
from vlln.oracle.classifier import model as classifier
from vlln.train.data import export_facts, read_export
from vlln.world.scene_summary.format import OBJECT_DICT_FILE, REGION_DICT_FILE
from vlln.world.scene_summary.reader import import_scene_summary

DEEP = b"[" * 100 + b"]" * 100  # past MAX_JSON_DEPTH (64)


def _house(folder: Path, info: bytes = b'{"format_version": "x"}', rows: bytes = b"") -> Path:
    (folder / "meta").mkdir(parents=True)
    (folder / INFO_FILE).write_bytes(info)
    (folder / EPISODES_FILE).write_bytes(rows)
    return folder


def _summary(folder: Path, regions: bytes) -> Path:
    folder.mkdir()
    (folder / REGION_DICT_FILE).write_bytes(regions)
    (folder / OBJECT_DICT_FILE).write_bytes(b"{}")
    return folder


# Each case: where the deep file goes (relative to tmp_path), what to write there first, and
# the call that reads it.
CASES: dict[str, tuple[str, Callable[[Path], object]]] = {
    "model card": (CARD_FILE, read_card),
    "house info": (INFO_FILE, lambda root: HouseDataset(root)),
    "build.json": (SETTINGS_FILE, recorded_strategy),
    "export.json": ("export.json", export_facts),
    "split stats": ("episodes/val_stats.json", lambda root: read_episode_stage(root / "episodes")),
    "trajectory journal": ("journal.jsonl", lambda root: read_journal(root / "journal.jsonl")),
}


@pytest.mark.parametrize("name", CASES)
def test_deeply_nested_json_is_one_line_naming_the_file(tmp_path: Path, name: str) -> None:
    relative, read = CASES[name]
    path = tmp_path / relative
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(DEEP + b"\n" + b"{}\n" if relative.endswith(".jsonl") else DEEP)
    with pytest.raises(DataFormatError) as info:
        read(tmp_path)
    message = str(info.value)
    assert str(path) in message
    assert "nested deeper than 64 levels" in message
    assert "\n" not in message


def test_a_deep_episodes_row_names_its_line(tmp_path: Path) -> None:
    root = _house(tmp_path / "house", rows=b'{"episode_index": 0}\n' + DEEP + b"\n")
    (root / INFO_FILE).unlink()  # optional: the reference's layout
    with pytest.raises(DataFormatError, match=rf"{root / EPISODES_FILE}:2: JSON nested deeper"):
        HouseDataset(root)


def test_a_deep_scene_summary_names_the_file(tmp_path: Path) -> None:
    folder = _summary(tmp_path / "house", DEEP)
    with pytest.raises(DataFormatError, match=rf"{folder / REGION_DICT_FILE} is not UTF-8 JSON"):
        import_scene_summary(folder)


def test_a_scene_summary_past_its_cap_says_how_to_raise_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("VLLN_MAX_SCENE_SUMMARY_MB", "1")
    folder = _summary(tmp_path / "house", b"{}")
    with (folder / REGION_DICT_FILE).open("wb") as handle:
        handle.truncate(2 << 20)  # sparse
    with pytest.raises(DataFormatError) as info:
        import_scene_summary(folder)
    assert str(info.value) == (
        f"{folder / REGION_DICT_FILE} holds more than 1 MiB, the cap on a scene-summary file; "
        "set VLLN_MAX_SCENE_SUMMARY_MB to more MiB if the file is right"
    )


def test_a_model_card_past_its_cap_is_one_line(tmp_path: Path) -> None:
    with (tmp_path / CARD_FILE).open("wb") as handle:
        handle.truncate(2 << 20)
    with pytest.raises(DataFormatError, match=r"more than 1 MiB, the cap on a model card; give"):
        read_card(tmp_path)


def test_sft_jsonl_is_capped_per_line_not_per_file(tmp_path: Path) -> None:
    (tmp_path / "export.json").write_text("{}")
    sample = {
        "id": "s",
        "images": [],
        "conversations": [
            {"from": "human", "value": "go " * 20_000},
            {"from": "gpt", "value": "ok"},
        ],
    }
    lines = (json.dumps(sample) + "\n").encode() * 24  # 1.4 MB: past a line's cap in all
    (tmp_path / "sft.jsonl").write_bytes(lines)
    assert len(read_export(tmp_path)) == 24
    with (tmp_path / "sft.jsonl").open("ab") as handle:
        handle.write(b" " * (2 << 20) + b"\n")
    with pytest.raises(DataFormatError) as info:
        read_export(tmp_path)
    assert str(info.value) == (
        f"{tmp_path / 'sft.jsonl'}, line 25 holds more than 1 MiB, the cap on a line of "
        "sft.jsonl; give the right file"
    )


def test_a_classifier_array_that_unpacks_past_its_cap_is_refused(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(classifier, "_UNPACKED_CAP", 1024)
    bomb = base64.b85encode(lzma.compress(b"\0" * 4096)).decode("ascii")
    with pytest.raises(ValueError, match="an array of more than 0 MiB"):
        classifier.unpacked(bomb)
    assert classifier.unpacked(base64.b85encode(lzma.compress(b"fits")).decode()) == b"fits"


def test_a_deep_classifier_artefact_is_damaged_not_a_traceback(tmp_path: Path) -> None:
    path = tmp_path / "question_classifier.json"
    path.write_bytes(DEEP)
    with pytest.raises(DataFormatError, match=rf"{path} is damaged \(JSON nested deeper"):
        classifier.load_classifier(path)


def test_a_trajectory_journal_line_that_is_not_json_text_names_its_line(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    good = json.dumps({"episode_id": "a", "episode_index": 0, "reason": None, "row": None})
    journal.write_bytes(b"\xff\xfe\n" + good.encode() + b"\n")
    with pytest.raises(DataFormatError, match=r"journal\.jsonl:1: unreadable journal line"):
        read_journal(journal)
