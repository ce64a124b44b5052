"""`vlln eval` as a command: a killed process resumes without loss, errors are one line."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.eval.runs import evaluate, lines
from vlln.cli import main
from vlln.eval.config import EvalConfig
from vlln.eval.runner import load_episodes
from vlln.tasks.episode import write_episodes
from vlln.tasks.scenes import SceneCache


def eval_args(out: Path, cache_dir: Path) -> list[str]:
    """The command line of the small run that ``tests.eval.runs.evaluate`` makes by default."""
    return [
        "eval", "--agent", "random", "--task", "iign", "--houses", "1", "--episodes", "4",
        "--budgets", "0-1", "--max-steps", "40", "--cache-dir", str(cache_dir), "--preset", "small",
        "--out", str(out), "--quiet",
    ]  # fmt: skip


@pytest.mark.slow
def test_killed_process_resumes_to_the_uninterrupted_result(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    reference = tmp_path / "reference"
    evaluate(reference, split_cache, scenes)
    out = tmp_path / "killed"
    results = out / "episodes.jsonl"
    command = [sys.executable, "-m", "vlln.cli", *eval_args(out, split_cache)]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60.0
    while process.poll() is None and time.monotonic() < deadline:
        if results.exists() and results.read_bytes().count(b"\n") >= 1:
            os.kill(process.pid, signal.SIGKILL)
            break
        time.sleep(0.01)
    process.wait(timeout=30)
    assert process.returncode == -signal.SIGKILL, process.stderr.read() if process.stderr else ""
    if process.stderr:
        process.stderr.close()
    assert 1 <= len(lines(out)) < 8  # killed in the middle
    outcome = evaluate(out, split_cache, scenes)
    assert outcome.complete
    assert lines(out) == lines(reference)  # another process, the same lines, none twice
    assert (out / "summary.json").read_bytes() == (reference / "summary.json").read_bytes()


@pytest.mark.slow
def test_ctrl_c_says_a_rerun_resumes_and_it_does(
    tmp_path: Path, split_cache: Path, scenes: SceneCache
) -> None:
    out = tmp_path / "interrupted"
    command = [sys.executable, "-m", "vlln.cli", *eval_args(out, split_cache)]
    # A shell runs background jobs with SIGINT ignored, and Python keeps it so; the child
    # gets the default back, so Ctrl-C reaches it wherever this suite runs.
    process = subprocess.Popen(
        command,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + 60.0
    while process.poll() is None and time.monotonic() < deadline:
        if (out / "episodes.jsonl").exists():
            process.send_signal(signal.SIGINT)
            break
        time.sleep(0.01)
    _, stderr = process.communicate(timeout=30)
    assert process.returncode == 130, stderr
    assert stderr.endswith("run the same command again to resume\n")
    assert evaluate(out, split_cache, scenes).complete


@pytest.mark.slow
def test_eval_command_writes_the_run_and_prints_the_summary(
    tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run"
    assert main([*eval_args(out, split_cache), "--stop-after", "2"]) == 0
    captured = capsys.readouterr()
    assert "2 of 8 episodes" in captured.err and "rerun the same command" in captured.err
    assert main(eval_args(out, split_cache)) == 0
    captured = capsys.readouterr()
    assert "8 of 8 episodes" in captured.err and "(complete)" in captured.err
    assert "| budget 1 | 4 |" in captured.out and "MSP (budgets 0..1)" in captured.out
    assert {p.name for p in out.iterdir()} >= {"run.json", "episodes.jsonl", "summary.json"}


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        (["--agent", "teleporter"], "teleporter"),
        (["--task", "pointnav"], "iign, ign, objectnav"),
        (["--shard", "2/2"], "shard 2/2 does not exist"),
        (["--budgets", "3-1"], "backwards"),
        (["--budgets", "0-7"], "dialog budgets run from 0 to 5, the paper's range"),
        (["--budgets", "0,9"], "dialog budgets run from 0 to 5, the paper's range"),
        (["--budgets", "0-99999999999999"], "the paper's range (its budget 5 already lets"),
        (
            ["--agent", "frontier", "--detector", "yolo"],
            "detector 'yolo'; choose one of: truth, noisy",
        ),
        (["--detector", "noisy"], "agent 'random' uses no detector"),
        (["--task", "objectnav"], "task objectnav has no dialog"),
    ],
)
def test_eval_errors_are_one_line_before_any_work(
    tmp_path: Path,
    split_cache: Path,
    capsys: pytest.CaptureFixture[str],
    changes: list[str],
    message: str,
) -> None:
    args = eval_args(tmp_path / "run", split_cache)
    for flag, value in zip(changes[::2], changes[1::2], strict=True):
        if flag in args:
            args[args.index(flag) + 1] = value
        else:
            args += [flag, value]
    assert main(args) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and message in error and error.count("\n") == 1
    assert not (tmp_path / "run").exists()


def test_eval_refuses_a_run_directory_with_other_arguments(
    tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "run"
    assert main([*eval_args(out, split_cache), "--stop-after", "0"]) == 0
    capsys.readouterr()
    assert main([*eval_args(out, split_cache), "--seed", "3"]) == 2
    error = capsys.readouterr().err
    assert "seed: 0 there, 3 now" in error and "another --out" in error


def test_episode_files_are_a_source_and_malformed_ones_give_the_readers_error(
    tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    config = EvalConfig(agent="random", task="iign", houses=1, preset="small")
    episode_file = tmp_path / "two_iign.json.gz"
    write_episodes(episode_file, load_episodes(config, split_cache, progress=False)[:2])
    args = ["eval", "--agent", "random", "--task", "iign", "--budget", "0", "--max-steps", "5"]
    assert main([*args, "--episode-file", str(episode_file), "--out", str(tmp_path / "a")]) == 0
    assert len(lines(tmp_path / "a")) == 2
    broken = tmp_path / "broken.json.gz"
    broken.write_bytes(b"not gzip at all")
    assert main([*args, "--episode-file", str(broken), "--out", str(tmp_path / "b")]) == 2
    error = capsys.readouterr().err
    assert "broken.json.gz is not a gzip file" in error
    assert not (tmp_path / "b").exists()
