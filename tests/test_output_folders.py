"""An --out that cannot be written (under a regular file, or on a read-only file system) is one
line naming the path and the fix, before any work, for eval, data build, data balance, report,
world export and world catalogue.

The read-only place is /sys: sysfs refuses new entries to every user, root included (root
ignores permission bits, so a chmod-ed folder would not fail under the tests' root)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from tests.tasks.test_metrics import make_record
from vlln.cli import main
from vlln.eval.config import EvalConfig
from vlln.eval.results import RunDirectory, load_run_records

READ_ONLY = Path("/sys/vlln-test-out")

COMMANDS = {
    "eval": ["eval", "--agent", "random", "--task", "iign", "--budget", "0", "--out"],
    "data build": ["data", "build", "--houses", "1", "--yes", "--out"],
    "data balance": ["data", "balance", "DATASET", "--out"],
    "report": ["report", "RUN", "--out"],
    "world export": ["world", "export", "--style", "mp3d", "--out"],
    "world catalogue": ["world", "catalogue", "--out"],
}


def command(name: str, out: Path, tmp_path: Path) -> list[str]:
    """The command writing to ``out``; report reads a finished run, which stays as it was."""
    run = RunDirectory(tmp_path / "run")
    run.prepare(EvalConfig(agent="random", task="iign"), planned=1)
    run.episodes_path.write_text(json.dumps(make_record().to_json()) + "\n")
    return [str(run.path) if arg == "RUN" else arg for arg in COMMANDS[name]] + [str(out)]


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_an_out_under_a_file_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    (tmp_path / "notes.txt").write_text("a file")
    out = tmp_path / "notes.txt" / "out"
    assert main(command(name, out, tmp_path)) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and error.startswith(f"error: --out {out} ")
    assert f"is under the file {tmp_path / 'notes.txt'}" in error and "give a folder" in error
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt", "run"]
    assert len(load_run_records([tmp_path / "run"])) == 1


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_an_out_on_a_read_only_file_system_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    with pytest.raises(OSError):
        os.mkdir(READ_ONLY)  # the premise: nobody may write there
    assert main(command(name, READ_ONLY, tmp_path)) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and error.startswith(f"error: --out {READ_ONLY}: ")
    assert "cannot write in /sys" in error and "give a folder you can write to" in error
