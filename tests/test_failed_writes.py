"""A full disk while writing a dataset, a training export, a scene export or a picture is one
WriteError line naming the file and the cause (files linked to /dev/full, where every write
fails with ENOSPC, or an fsync that fails so), and what was written before stays for the
rerun; the commands print that line alone, with no traceback."""

from __future__ import annotations

import errno
import os
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from vlln.cli import main
from vlln.datagen.layout import JOURNAL_FILE
from vlln.datagen.sft import export
from vlln.datagen.sft.images import ImageStore, image_name
from vlln.datagen.writer import HouseWriter, read_journal
from vlln.errors import WriteError
from vlln.prompt import ImageRef
from vlln.prompt.images import stored_frame
from vlln.sim.camera import CameraSpec
from vlln.world.catalogue import default_catalogue


def _full(path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.symlink_to("/dev/full")
    return path


def _full_disk_line(path: Path) -> str:
    return (
        f"cannot write {path}: No space left on device; free some space or make the folder "
        "writable, then run the same command again"
    )


def _is_one_line_for(error: pytest.ExceptionInfo[WriteError], path: Path) -> None:
    assert str(error.value) == _full_disk_line(path)


def _no_space(fd: int) -> None:
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def test_a_full_disk_at_a_journal_line_keeps_the_attempts_before(tmp_path: Path) -> None:
    writer = HouseWriter(tmp_path, "house_00001", CameraSpec())
    writer.write_rejected("e0", "too short")
    journal = writer.root / JOURNAL_FILE
    kept = journal.read_bytes()
    journal.rename(journal.with_name("kept.jsonl"))
    _full(journal)
    with pytest.raises(WriteError) as error:
        writer.write_rejected("e1", "too short")
    _is_one_line_for(error, journal)
    journal.unlink()
    journal.with_name("kept.jsonl").rename(journal)
    assert journal.read_bytes() == kept
    assert list(read_journal(journal)) == ["e0"]  # the rerun tries e1 again


def test_a_full_disk_at_a_trajectory_file_is_one_line(tmp_path: Path) -> None:
    writer = HouseWriter(tmp_path, "house_00001", CameraSpec())
    path = _full(writer.root / "data" / "chunk-000" / "episode_000000.parquet")
    with pytest.raises(WriteError) as error:
        writer._write("data/chunk-000/episode_000000.parquet", b"PAR1")
    _is_one_line_for(error, path)


def test_a_full_disk_at_an_exported_image_is_one_line(tmp_path: Path) -> None:
    frame = tmp_path / "frame.jpg"
    frame.write_bytes(stored_frame(np.zeros((48, 64, 3), np.uint8)))
    house: Any = SimpleNamespace(root=tmp_path / "house_00001", image_file=lambda *_: frame)
    ref = ImageRef("level", 0)
    store = ImageStore(tmp_path / "out")
    path = _full(store.out / image_name("house_00001", 0, ref))
    with pytest.raises(WriteError) as error:
        store.add(house, 0, ref)
    _is_one_line_for(error, path)
    assert not store.written


def test_a_failed_sft_jsonl_is_one_line_and_leaves_no_temporary_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(export.os, "fsync", _no_space)
    path = tmp_path / "sft.jsonl"
    with pytest.raises(WriteError) as error, export._lines_atomic(path) as sink:
        sink.write("{}\n")
    _is_one_line_for(error, path)
    assert list(tmp_path.iterdir()) == []


def test_a_full_disk_at_a_world_export_is_one_line_and_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(os, "fsync", _no_space)
    out = tmp_path / "scenes"
    assert main(["world", "export", "--style", "mp3d", "--out", str(out)]) == 2
    glb = out / "mp3d" / "house_00000" / "house_00000.glb"
    assert capsys.readouterr().err == f"error: {_full_disk_line(glb)}\n"
    assert [path for path in out.rglob("*") if path.is_file()] == []


def test_a_full_disk_at_a_catalogue_picture_stops_the_command_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    first = next(iter(default_catalogue())).name.replace(" ", "_")
    picture = _full(tmp_path / "catalogue" / f"{first}.png")
    assert main(["world", "catalogue", "--out", str(picture.parent)]) == 2
    assert capsys.readouterr().err == f"error: {_full_disk_line(picture)}\n"
    assert list(picture.parent.iterdir()) == [picture]  # stopped at the first picture
