"""Damaged, partial or degraded runs are read without a crash and reported as what they are:
resume and score never fail on a bad line or count an episode twice, and every reading
command states incomplete runs, skipped lines and failed or fallback turns."""

from __future__ import annotations

import gzip
import json
import shutil
from dataclasses import asdict, replace
from pathlib import Path

import pytest

from tests.eval.runs import evaluate, lines
from tests.eval.test_cli import eval_args
from vlln.cli import main
from vlln.eval.results import SKIPPED_FILE
from vlln.tasks.episode import write_episodes
from vlln.tasks.record import DialogTurn
from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import load_or_build_split


@pytest.fixture(scope="module")
def full_run(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> Path:
    out = tmp_path_factory.mktemp("health")
    assert evaluate(out, split_cache, scenes).complete
    return out


def copy_run(full_run: Path, to: Path) -> Path:
    shutil.copytree(full_run, to)
    return to


@pytest.mark.slow
def test_wrong_types_neither_crash_resume_and_score_nor_duplicate(
    full_run: Path, tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 1: `"steps": "lots"`, `"budget": -3` in one line."""
    run = copy_run(full_run, tmp_path / "run")
    original = lines(run)
    broken = json.loads(original[2]) | {"steps": "lots", "budget": -3}
    (run / "episodes.jsonl").write_text(
        "\n".join([*original[:2], json.dumps(broken), *original[3:]]) + "\n"
    )
    assert main(["score", str(run)]) == 0
    err = capsys.readouterr().err
    assert "INCOMPLETE, 7 of 8" in err and "episodes.jsonl:3" in err and "'budget'" in err
    assert main(eval_args(run, split_cache)) == 0
    err = capsys.readouterr().err
    assert "repaired:" in err and "complete, 8 of 8" in err
    assert sorted(lines(run)) == sorted(original)  # one line per episode, 8 for 8
    assert (run / SKIPPED_FILE).read_text().strip() == json.dumps(broken)
    assert main(["score", str(run)]) == 0
    assert f"set aside in {SKIPPED_FILE} 1" in capsys.readouterr().err


@pytest.mark.slow
def test_lines_outside_the_plan_do_not_stand_in_for_planned_episodes(
    full_run: Path, tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Two planned lines replaced by an episode and a budget the run does not plan: still
    8 lines, but 6 of the 8 planned; a resume plays the two and sets the others aside."""
    run = copy_run(full_run, tmp_path / "run")
    original = lines(run)
    stranger = json.loads(original[0]) | {"episode_id": "not-in-the-plan"}
    other_budget = json.loads(original[1]) | {"budget": 5}
    foreign = [json.dumps(stranger), json.dumps(other_budget)]
    (run / "episodes.jsonl").write_text("\n".join([*foreign, *original[2:]]) + "\n")
    assert main(["score", str(run), "--json"]) == 0
    captured = capsys.readouterr()
    assert "INCOMPLETE, 6 of 8" in captured.err and "unplanned 2" in captured.err
    assert "episode not-in-the-plan" in captured.err
    health = json.loads(captured.out)["health"]
    assert health["complete"] is False and health["finished"] == 6
    assert main(eval_args(run, split_cache)) == 0
    err = capsys.readouterr().err
    assert "played 2" in err and "8 of 8 episodes" in err and "complete, 8 of 8" in err
    assert sorted(lines(run)) == sorted(original)
    assert (run / SKIPPED_FILE).read_text().splitlines() == foreign
    assert main(["score", str(run)]) == 0
    assert "complete, 8 of 8" in capsys.readouterr().err


@pytest.mark.slow
def test_lines_of_another_run_are_named_not_counted_and_set_aside(
    full_run: Path, tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Three planned lines replaced by the same episodes played by another agent, on another
    task and with a detector: 5 of 8, no table of the strangers; a resume plays the three."""
    run = copy_run(full_run, tmp_path / "run")
    original = lines(run)
    changes = [{"agent": "expert"}, {"task": "ign"}, {"detector": "noisy"}]
    strangers = [
        json.dumps(json.loads(line) | change)
        for line, change in zip(original[:3], changes, strict=True)
    ]
    (run / "episodes.jsonl").write_text("\n".join([*strangers, *original[3:]]) + "\n")
    assert main(["score", str(run), "--json"]) == 0
    captured = capsys.readouterr()
    assert "INCOMPLETE, 5 of 8" in captured.err and "another run 3" in captured.err
    assert "was played by expert on iign, not by this run's random on iign" in captured.err
    (group,) = json.loads(captured.out)["groups"]
    assert (group["agent"], group["detector"], group["task"]) == ("random", None, "iign")
    assert main(eval_args(run, split_cache)) == 0
    err = capsys.readouterr().err
    assert "played 3" in err and "complete, 8 of 8" in err
    assert sorted(lines(run)) == sorted(original)
    assert (run / SKIPPED_FILE).read_text().splitlines() == strangers


def test_torn_last_line_is_stated_and_a_line_missing_its_newline_is_kept(
    full_run: Path, tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 3."""
    run = copy_run(full_run, tmp_path / "run")
    data = (run / "episodes.jsonl").read_bytes()
    (run / "episodes.jsonl").write_bytes(data[:-30])
    assert main(["score", str(run), "--json"]) == 0
    captured = capsys.readouterr()
    assert "INCOMPLETE, 7 of 8" in captured.err and "torn 1" in captured.err
    health = json.loads(captured.out)["health"]
    assert health["complete"] is False and health["skipped_lines"] == {"torn": 1}
    (run / "episodes.jsonl").write_bytes(data[:-1])
    assert main(["score", str(run)]) == 0
    assert "complete, 8 of 8" in capsys.readouterr().err
    assert main(eval_args(run, split_cache)) == 0
    assert "played 0" in capsys.readouterr().err  # kept, not cut and replayed
    assert (run / "episodes.jsonl").read_bytes() == data


@pytest.mark.slow
def test_fallback_turns_are_counted_and_run_json_names_who_played(
    full_run: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 4: an LLM oracle that fell back to rules on every turn."""
    run = copy_run(full_run, tmp_path / "run")
    provenance = json.loads((run / "run.json").read_text())["provenance"]
    assert provenance == {
        "agent": "random",
        "oracle": "RuleOracle",
        "backend": "rules",
        "model": None,
    }
    records = [json.loads(text) for text in lines(run)]
    turns = 0
    for record in records:
        if record["budget"] > 0:
            turn = DialogTurn(1, "which way?", "left", "route", True, "openai:m@h", fallback=True)
            record["dialog"] = [asdict(turn)]
            turns += 1
    (run / "episodes.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    # Every turn fell back, so the scores measure the oracle's server: said, and exit 1.
    assert main(["score", str(run)]) == 1
    error = capsys.readouterr().err
    assert f"oracle fallback turns {turns}" in error
    assert f"error: the oracle's model answered none of {turns} questions" in error
    assert main(["report", str(run), "--out", str(tmp_path / "report")]) == 0
    report = (tmp_path / "report" / "report.md").read_text()
    assert "## Run health" in report and f"oracle fallback turns {turns}" in report


def test_path_arguments_of_the_wrong_kind_are_one_line_errors(
    full_run: Path, tmp_path: Path, split_cache: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 2: --out naming an existing file."""
    file = tmp_path / "a_file"
    file.write_text("keep me")
    for args in (eval_args(file, split_cache), ["report", str(full_run), "--out", str(file)]):
        assert main(args) == 2
        error = capsys.readouterr().err
        assert error.startswith("error: ") and "is a file" in error and error.count("\n") == 1
    assert file.read_text() == "keep me"


def test_an_empty_episode_file_is_an_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 10, second half."""
    empty = tmp_path / "empty.json.gz"
    write_episodes(empty, [])
    args = ["eval", "--agent", "random", "--task", "iign", "--episode-file", str(empty)]
    assert main([*args, "--out", str(tmp_path / "run")]) == 2
    error = capsys.readouterr().err
    assert "holds no episodes" in error and error.count("\n") == 1


def test_an_episode_file_with_a_repeated_id_is_refused_at_load(
    split_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Two episodes under one id would both be played and one set aside, so the run could
    never complete; the file is refused in one line before anything is played."""
    episodes = load_or_build_split("test", "iign", 1, split_cache, progress=False)[:3]
    repeated = tmp_path / "repeated.json.gz"
    items = [
        e.to_json() for e in (*episodes, replace(episodes[2], episode_id=episodes[0].episode_id))
    ]
    repeated.write_bytes(gzip.compress(json.dumps({"episodes": items}).encode()))
    args = ["eval", "--agent", "random", "--task", "iign", "--episode-file", str(repeated)]
    assert main([*args, "--out", str(tmp_path / "run")]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1
    assert f"episodes 0 and 3 share episode_id {episodes[0].episode_id!r}" in error
    assert not (tmp_path / "run" / "episodes.jsonl").exists()


@pytest.mark.parametrize(
    "args",
    [
        [
            "eval",
            "--agent",
            "random",
            "--task",
            "iign",
            "--episode-file",
            "{dir}",
            "--out",
            "{new}",
        ],
        ["data", "build", "--houses", "1", "--out", "{file}", "--yes"],
        ["score", "{file}"],
        ["world", "show", "--out", "{file}"],
    ],
)
def test_every_path_of_the_wrong_kind_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], args: list[str]
) -> None:
    """Reproductions 2 and 10: a folder for a file, a file for a folder."""
    (tmp_path / "file").write_text("x")
    places = {
        "{dir}": str(tmp_path),
        "{file}": str(tmp_path / "file"),
        "{new}": str(tmp_path / "n"),
    }
    assert main([places.get(arg, arg) for arg in args]) == 2
    error = capsys.readouterr().err
    assert error.startswith("error: ") and error.count("\n") == 1
