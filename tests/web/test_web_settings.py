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


def test_agent_options_are_read_into_the_agents_options_class(
    study: Study, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = ["serve", "web", "--episode-file", str(study.episode_file), "--out", str(tmp_path)]
    options = ["--agent-option", "openai-vlm.base_url=http://127.0.0.1:9/v1"]
    options += ["--agent-option", "openai-vlm.model=m", "--agent-option", "openai-vlm.timeout_s=x"]
    assert main([*source, *options]) == 2
    error = capsys.readouterr().err
    assert error == (
        "error: openai-vlm option timeout_s = 'x': Input should be a valid number, "
        "unable to parse string as a number\n"
    )
    assert main([*source, "--agent-option", "fbe.model=m"]) == 2
    assert capsys.readouterr().err == "error: agent 'fbe' takes no options, got model\n"
    assert main([*source, "--agent-option", "frontier.model=m"]) == 2
    assert capsys.readouterr().err == (
        "error: unknown frontier option 'model'; known: dialog_policy\n"
    )
