"""``vlln eval --agent package.module:Class``: the documented example agent plays built-in
episodes end to end, and every wrong name is one line before any work."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from vlln.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"


def test_the_guide_shows_the_example_file_as_it_is() -> None:
    guide = (ROOT / "docs" / "own-agent.md").read_text(encoding="utf-8")
    shown = re.search(r"```python\n(.*?)```", guide, re.DOTALL)
    assert shown is not None
    assert shown.group(1) == (EXAMPLES / "own_agent.py").read_text(encoding="utf-8")


@pytest.mark.slow
def test_the_example_agent_plays_episodes_through_vlln_eval(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(EXAMPLES)  # as the guide runs it: the module in the current folder
    out = tmp_path / "run"
    argv = ["eval", "--agent", "own_agent:DepthWalker", "--task", "iign", "--houses", "1"]
    argv += ["--episodes", "2", "--out", str(out), "--cache-dir", str(tmp_path / "cache")]
    assert main([*argv, "--quiet"]) == 0
    assert "complete, 2 of 2 episode lines" in capsys.readouterr().err
    records = [json.loads(line) for line in (out / "episodes.jsonl").read_text().splitlines()]
    assert len(records) == 2
    for record in records:
        assert record["agent"] == "own_agent:DepthWalker" and record["error"] is None
        # Its one question, answered by the oracle, then its walk to step 80 and STOP.
        (turn,) = record["dialog"]
        assert turn["question"] == f"Which way is the {record['object_category']}?"
        assert turn["answered"] and turn["answer"]
        assert record["actions"][0] == "TALK" and record["actions"][-1] == "STOP"
        assert record["steps"] == 80 and record["end_reason"] == "stop"
        assert record["path_length"] > 2.0
        assert {"MOVE_FORWARD", "TURN_LEFT", "TURN_RIGHT"} <= set(record["actions"])
    # The same seeds give the same records on a rerun elsewhere.
    again = tmp_path / "again"
    assert main([*argv[:-3], str(again), *argv[-2:], "--quiet"]) == 0
    assert (again / "episodes.jsonl").read_text() == (out / "episodes.jsonl").read_text()


BROKEN = """
class NoSeed:
    name = "no-seed"
    privileged = False

    def __init__(self) -> None:
        pass


class Halfway:
    name = "halfway"

    def __init__(self, seed: int) -> None:
        self.privileged = "no"

    def reset(self, episode): ...
"""


@pytest.mark.parametrize(
    ("spec", "says"),
    [
        ("own_agent", "unknown agent 'own_agent'; choose one of: aiuta, expert, fbe, frontier"),
        ("own_agent:", "--agent 'own_agent:': name an agent class as package.module:Class"),
        (":DepthWalker", "--agent ':DepthWalker': name an agent class as package.module:Class"),
        ("nowhere_at_all:Agent", "no module named nowhere_at_all; run from the folder"),
        ("own_agent:Walker", "module own_agent has no Walker; it has: Action, DepthWalker"),
        ("json:dumps", "--agent json:dumps: dumps in json is not a class"),
        ("broken:NoSeed", "NoSeed(seed) failed: TypeError: "),
        (
            "broken:Halfway",
            "Halfway does not implement the agent protocol (vlln.agents.protocol.Agent); "
            "it lacks act, privileged (a bool); see docs/own-agent.md",
        ),
        (
            "fractions:Fraction",
            "it lacks reset, act, name (a str), privileged (a bool)",
        ),
        ("syntax_error:Agent", "importing syntax_error failed: SyntaxError: invalid syntax"),
        ("needs_more:Agent", "importing needs_more failed: No module named 'not_installed_here'"),
    ],
)
def test_a_wrong_agent_name_is_one_line_before_any_work(
    spec: str,
    says: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    modules = tmp_path / "modules"
    modules.mkdir()
    (modules / "own_agent.py").write_text((EXAMPLES / "own_agent.py").read_text())
    (modules / "broken.py").write_text(BROKEN)
    (modules / "syntax_error.py").write_text("class Agent(:\n")
    (modules / "needs_more.py").write_text("import not_installed_here\n")
    monkeypatch.chdir(modules)
    out = tmp_path / "run"
    argv = ["eval", "--agent", spec, "--task", "iign", "--houses", "1", "--episodes", "1"]
    assert main([*argv, "--out", str(out), "--cache-dir", str(tmp_path / "cache")]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and error.startswith("error: "), error
    assert says in error
    assert not out.exists() and not (tmp_path / "cache").exists()
