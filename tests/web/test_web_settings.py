"""A damaged web.json in a study folder is one line naming it and the fix, and the study's
finished records are left as they were."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.web.conftest import Study
from vlln.cli import main

DAMAGE = {
    "not JSON": b'{"source": "split',
    "a list": b"[1, 2]",
    "a string": b'"settings"',
    "binary": bytes(range(256)),
    "a 5000-digit number": b'{"episodes": ' + b"9" * 5000 + b"}",
    "deep nesting": b"[" * 5000 + b"]" * 5000,
}


@pytest.mark.parametrize("kind", sorted(DAMAGE))
def test_a_damaged_web_json_is_one_line(
    study: Study, tmp_path: Path, capsys: pytest.CaptureFixture[str], kind: str
) -> None:
    out = tmp_path / "study"
    out.mkdir()
    (out / "web.json").write_bytes(DAMAGE[kind])
    (out / "episodes.jsonl").write_bytes(b"")
    source = ["--episode-file", str(study.episode_file)]
    assert main(["serve", "web", *source, "--out", str(out)]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"error: {out / 'web.json'} is damaged (") and error.count("\n") == 1
    assert "restore the study's settings, or serve into another --out" in error
    assert (out / "web.json").read_bytes() == DAMAGE[kind]
