"""The project's one file writer: atomic writes, the leftovers of a killed one removed, and
output folders checked before any work."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.errors import ConfigError
from vlln.files import check_output_folder, remove_leftover_temp_files, write_text_atomic


def test_an_atomic_write_leaves_only_the_file(tmp_path: Path) -> None:
    path = tmp_path / "meta" / "info.json"
    write_text_atomic(path, "{}\n")
    write_text_atomic(path, '{"a": 1}\n')
    assert path.read_text() == '{"a": 1}\n'
    assert sorted(p.name for p in path.parent.iterdir()) == ["info.json"]


def test_leftovers_of_a_killed_write_are_removed_and_nothing_else(tmp_path: Path) -> None:
    meta = tmp_path / "house_00001" / "meta"
    meta.mkdir(parents=True)
    (meta / ".info.json.k2j4.tmp").write_text("half")
    (meta / ".episodes.jsonl.x9.tmp").write_text("half")
    (meta / "episodes.jsonl").write_text("{}\n")
    (meta / ".hidden").write_text("kept")
    (meta / "notes.tmp").write_text("kept: not the writer's name")
    remove_leftover_temp_files(tmp_path / "house_00001")
    assert sorted(p.name for p in meta.iterdir()) == [".hidden", "episodes.jsonl", "notes.tmp"]
    remove_leftover_temp_files(tmp_path / "missing")  # a house not started yet


def test_a_writable_folder_passes_and_the_probe_leaves_nothing(tmp_path: Path) -> None:
    check_output_folder(tmp_path / "new" / "deeper")
    check_output_folder(tmp_path)
    assert list(tmp_path.iterdir()) == []
    (tmp_path / "file").write_text("x")
    with pytest.raises(ConfigError, match="is a file, not a folder"):
        check_output_folder(tmp_path / "file")
