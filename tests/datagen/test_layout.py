"""The trajectory folder's resume journal."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from vlln.datagen.writer import read_journal
from vlln.errors import DataFormatError


def _line(episode_id: str, index: int | None) -> str:
    row = {"episode_id": episode_id, "episode_index": index, "reason": None, "row": None}
    return json.dumps(row)


def test_a_torn_last_line_is_cut_and_the_rest_kept(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text(_line("a", 0) + "\n" + _line("b", 1) + "\n" + '{"episode_id": "c", "epi')
    attempts = read_journal(journal)
    assert list(attempts) == ["a", "b"]
    assert journal.read_text() == _line("a", 0) + "\n" + _line("b", 1) + "\n"


def test_a_whole_last_line_without_newline_is_kept(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text(_line("a", 0) + "\n" + _line("b", None))
    assert list(read_journal(journal)) == ["a", "b"]
    assert journal.read_text().endswith("\n")


def test_damage_before_the_last_line_is_an_error(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text("not json\n" + _line("b", 0) + "\n")
    with pytest.raises(DataFormatError, match=r"journal\.jsonl:1"):
        read_journal(journal)
