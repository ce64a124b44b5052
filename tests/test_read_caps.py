"""Bounded reads: a gzip bomb, an endless ``--config`` and a file past its cap are one line that
names the cap and how to raise it, read no further than the cap."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest

from vlln.cli import main
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.results import RESULTS_CAP, scan_records
from vlln.tasks.episode import EPISODE_FILE_CAP, read_episodes


def bomb(path: Path, mib: int) -> Path:
    """A gzip file of ``mib`` MiB of spaces, some kilobytes on disk: a valid JSON prefix."""
    path.write_bytes(gzip.compress(b'{"episodes": [' + b" " * (mib << 20), compresslevel=9))
    return path


def test_a_gzip_bomb_stops_at_the_episode_file_cap(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    path = bomb(tmp_path / "val_iign.json.gz", 8)
    assert path.stat().st_size < 50_000
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message == (
        f"{path} holds more than 1 MiB after decompression, the cap on an episode file; "
        "set VLLN_MAX_EPISODE_FILE_MB to more MiB if the file is right"
    )


def test_a_bad_cap_setting_is_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VLLN_MAX_EPISODE_FILE_MB", "lots")
    with pytest.raises(ConfigError, match="VLLN_MAX_EPISODE_FILE_MB='lots': give a whole"):
        read_episodes(bomb(tmp_path / "e.json.gz", 1))


def test_config_from_dev_zero_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["eval", "--config", "/dev/zero", "--out", "o"]) == 2
    assert capsys.readouterr().err == (
        "error: --config /dev/zero: /dev/zero holds more than 1 MiB, the cap on a settings "
        "file; give the right file\n"
    )


def test_a_results_file_past_its_cap_is_one_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(RESULTS_CAP.variable or "", "1")
    path = tmp_path / "episodes.jsonl"
    with path.open("wb") as handle:
        handle.truncate((1 << 20) + 1)  # sparse: no disk used
    with pytest.raises(DataFormatError, match="VLLN_MAX_RESULTS_FILE_MB"):
        scan_records(path)
