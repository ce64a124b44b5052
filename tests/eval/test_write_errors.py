"""A full disk or a folder that cannot be written is one line naming the file and the cause
(vlln.errors.WriteError, printed by the command line), never a traceback."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.tasks.test_metrics import make_record
from vlln.errors import WriteError
from vlln.eval.results import RecordWriter, RunDirectory


def test_a_full_disk_at_a_record_is_one_line_naming_the_file() -> None:
    with open("/dev/full", "ab", buffering=0) as handle:  # every write: ENOSPC
        writer = RecordWriter(handle, [], [])
        with pytest.raises(WriteError) as info:
            writer.append(make_record(episode_id="e0"))
    assert str(info.value) == (
        "cannot write /dev/full: No space left on device; free some space or make the folder "
        "writable, then run the same command again"
    )
    assert writer.records == []


def test_a_summary_that_cannot_be_written_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    run = RunDirectory(tmp_path / "file" / "run")  # under a file: no folder can be made there
    with pytest.raises(WriteError) as info:
        run.write_summary({}, "")
    assert str(info.value).startswith(f"cannot write {run.path / 'summary.json'}: ")
    assert "\n" not in str(info.value)
