"""Model and oracle servers that fail: checked before the first episode, given up on after a
few failed requests in a row (the run stops, its finished lines kept), and a run in which a
server never answered exits non-zero. Every misbehaving mode is played against both servers,
with a short deadline, no retries and a limit of two failures so that each test takes a
second or so."""

from __future__ import annotations

import json
import socket
from pathlib import Path
from typing import Any

import pytest

from tests.eval.runs import agent_factory
from tests.oracle.llm.chat_server import MISBEHAVING, chat_server, completion, misbehaving
from vlln.cli import main
from vlln.errors import ServerDownError
from vlln.eval.config import EvalConfig
from vlln.eval.runner import RunOutcome, run_evaluation
from vlln.tasks.episode import write_episodes
from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import load_or_build_split

MODEL_FLAGS = ["--model-timeout", "0.3", "--model-retries", "0", "--model-max-failures", "2"]
ORACLE_FLAGS = ["--oracle-timeout", "0.3", "--oracle-retries", "0", "--oracle-max-failures", "2"]


@pytest.fixture
def two_episodes(split_cache: Path, tmp_path: Path) -> str:
    path = tmp_path / "two.json.gz"
    write_episodes(path, load_or_build_split("test", "iign", 1, split_cache, progress=False)[:2])
    return str(path)


def play(source: str, out: Path, scenes: SceneCache, **settings: Any) -> RunOutcome:
    config = EvalConfig(task="iign", split=None, episode_file=source, max_steps=6, **settings)
    factory = agent_factory if config.agent == "talking" else None
    return run_evaluation(config, out, progress=False, scenes=scenes, agent_factory=factory)


def play_model(url: str, source: str, out: Path, scenes: SceneCache) -> RunOutcome:
    options = {"base_url": url, "model": "m", "timeout_s": 0.3, "max_retries": 0, "max_failures": 2}
    return play(source, out, scenes, agent="openai-vlm", budgets=(0,), agent_options=options)


def play_oracle(url: str, source: str, out: Path, scenes: SceneCache) -> RunOutcome:
    settings = {"oracle_timeout": 0.3, "oracle_retries": 0, "oracle_max_failures": 2}
    return play(
        source, out, scenes, agent="talking", budgets=(5,), oracle="llm", oracle_model="m",
        oracle_base_url=url, **settings,
    )  # fmt: skip


def episode_lines(out: Path) -> list[dict[str, Any]]:
    path = out / "episodes.jsonl"
    return [json.loads(line) for line in path.open()] if path.exists() else []


@pytest.mark.parametrize("mode", MISBEHAVING)
def test_a_failing_model_server_stops_the_run_and_keeps_the_finished_lines(
    mode: str, two_episodes: str, scenes: SceneCache, tmp_path: Path
) -> None:
    out = tmp_path / "run"
    with chat_server([completion("<move>STOP"), misbehaving(mode)]) as server:
        with pytest.raises(ServerDownError, match="failed 2 requests in a row"):
            play_model(server.base_url, two_episodes, out, scenes)
        assert len(server.requests) == 3  # the first episode's STOP, then two failures
    (finished,) = episode_lines(out)
    assert finished["actions"] == ["STOP"]
    health = json.loads((out / "summary.json").read_text())["health"]
    assert (health["complete"], health["finished"], health["planned"]) == (False, 1, 2)


@pytest.mark.parametrize("mode", MISBEHAVING)
def test_a_failing_oracle_server_stops_the_run(
    mode: str, two_episodes: str, scenes: SceneCache, tmp_path: Path
) -> None:
    with chat_server([misbehaving(mode)]) as server:
        with pytest.raises(ServerDownError, match="failed 2 requests in a row"):
            play_oracle(server.base_url, two_episodes, tmp_path / "run", scenes)
        assert len(server.requests) == 2
    assert episode_lines(tmp_path / "run") == []


def test_a_model_that_never_gives_a_readable_reply_measures_nothing(
    two_episodes: str, scenes: SceneCache, tmp_path: Path
) -> None:
    with chat_server([completion("I see a hallway.")]) as server:
        outcome = play_model(server.base_url, two_episodes, tmp_path / "run", scenes)
    assert outcome.complete and len(outcome.records) == 2
    calls = sum(len(record.model_calls) for record in outcome.records)
    assert outcome.health.unmeasured == [f"none of {calls} model calls gave a readable reply"]
    assert f"NOTHING MEASURED: none of {calls} model calls" in outcome.health.line()


@pytest.mark.slow
def test_a_run_whose_oracle_never_answered_exits_non_zero(
    two_episodes: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["eval", "--agent", "tests.eval.runs:TalkingAgent", "--task", "iign", "--quiet"]
    args += ["--episode-file", two_episodes, "--max-steps", "6", "--out", str(tmp_path / "run")]
    with chat_server([completion("a question, I think")]) as server:  # names no type
        oracle = ["--oracle", "llm", "--oracle-model", "m", "--oracle-base-url", server.base_url]
        assert main([*args, *oracle, *ORACLE_FLAGS]) == 1
    error = capsys.readouterr().err
    assert "NOTHING MEASURED: the oracle's model answered none of 6 questions" in error
    assert error.splitlines()[-1].startswith("error: the oracle's model answered none of 6")
    assert len(episode_lines(tmp_path / "run")) == 2  # kept, for what they are


def test_an_unreachable_oracle_server_is_refused_before_any_episode(
    two_episodes: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    with socket.socket() as taken:  # a loopback port nothing listens on once it is closed
        taken.bind(("127.0.0.1", 0))
        url = f"http://127.0.0.1:{taken.getsockname()[1]}/v1"
    args = ["eval", "--agent", "random", "--task", "iign", "--quiet", "--out", str(tmp_path)]
    args += ["--episode-file", two_episodes, "--oracle", "llm", "--oracle-model", "m"]
    assert main([*args, "--oracle-base-url", url]) == 2
    error = capsys.readouterr().err
    assert (
        error == (f"error: the model server at {url} does not answer ({error.split('(', 1)[1]}")
        and error.count("\n") == 1
    )
    assert error.rstrip().endswith("start it, or fix --oracle-base-url")
    assert not (tmp_path / "episodes.jsonl").exists()


@pytest.mark.slow
def test_the_model_flags_stop_a_trickling_server_in_one_line(
    two_episodes: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["eval", "--agent", "openai-vlm", "--task", "iign", "--budget", "0", "--quiet"]
    args += ["--episode-file", two_episodes, "--model", "m", "--out", str(tmp_path / "run")]
    with chat_server([misbehaving("trickle")]) as server:
        assert main([*args, "--base-url", server.base_url, *MODEL_FLAGS]) == 2
    (line,) = capsys.readouterr().err.splitlines()
    assert line.startswith("error: openai:m@127.0.0.1 failed 2 requests in a row (last: no ")
    assert "0.3 s deadline" in line and line.endswith("rerun the same command")
