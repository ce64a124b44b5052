"""Hostile episode files: integers of thousands of digits, floats past the float range and deep
nesting are refused in one line naming the file, through the reader and through `vlln eval`."""

from __future__ import annotations

import gzip
import json
from pathlib import Path

import pytest

from tests.tasks.test_episode import raw_episode
from vlln.cli import main
from vlln.errors import DataFormatError
from vlln.tasks.episode import read_episodes


def hostile_file(path: Path, field: str, text: str) -> Path:
    """An episode file whose one episode has ``field`` written as the raw JSON ``text``."""
    document = json.dumps({"episodes": [raw_episode() | {field: "@"}]}).replace('"@"', text)
    path.write_bytes(gzip.compress(document.encode()))
    return path


HOSTILE = {
    "5000-digit id": ("episode_id", "9" * 5000, "integer of 5000 digits"),
    "400-digit coordinate": ("start_position", "[" + "9" * 400 + ", 0, 0]", "400 digits"),
    "400-digit float": ("start_position", "[" + "9" * 400 + ".5, 0, 0]", "3 finite numbers"),
    "deep nesting": ("info", '{"a": ' + "[" * 5000 + "]" * 5000 + "}", "nested deeper"),
    "nesting under the parser's limit": ("info", "[" * 950 + "]" * 950, "nested deeper"),
    "a lone surrogate in a text": ("episode_id", '"7\\udfff"', "lone UTF-16 surrogate"),
}


@pytest.mark.parametrize("kind", sorted(HOSTILE))
def test_the_reader_refuses_in_one_line(tmp_path: Path, kind: str) -> None:
    field, text, reason = HOSTILE[kind]
    path = hostile_file(tmp_path / "val_iign.json.gz", field, text)
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message.startswith(str(path)) and reason in message
    assert "\n" not in message and len(message) < 300


def test_eval_refuses_a_hostile_episode_file_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = hostile_file(tmp_path / "val_iign.json.gz", "episode_id", "9" * 5000)
    args = ["eval", "--agent", "random", "--task", "iign", "--budget", "0"]
    assert main([*args, "--episode-file", str(path), "--out", str(tmp_path / "run")]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and error.count("\n") == 1 and "5000 digits" in error
