"""Hostile numbers in results lines: integers of thousands of digits, floats past the float range,
deep nesting and counters that the trace contradicts are skipped and named like any invalid
line; score, report and a resume go on, and the valid lines are all kept."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.eval.runs import evaluate, lines
from tests.eval.test_cli import eval_args
from tests.tasks.test_metrics import make_record
from vlln.cli import main
from vlln.eval.config import EvalConfig
from vlln.eval.results import SKIPPED_FILE, RunDirectory, load_runs, scan_records
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache


def line(record: EpisodeRecord) -> str:
    return json.dumps(record.to_json())


def raw(episode_id: str, field: str, text: str) -> str:
    """A record whose ``field`` is written as the raw JSON ``text``."""
    data = make_record(episode_id=episode_id).to_json() | {field: "@"}
    return json.dumps(data).replace('"@"', text)


HOSTILE = {
    "5000-digit integer": raw("x", "steps", "9" * 5000),
    "400-digit integer": raw("x", "budget", "9" * 400),
    "400-digit number in a distance": raw("x", "path_length", "9" * 400),
    "400-digit float": raw("x", "geodesic_start", "9" * 400 + ".5"),
    "400-digit distance in the trace": raw("x", "geodesic_trace", "[" + "9" * 400 + "]"),
    "huge token count": raw(
        "x",
        "dialog",
        '[{"step": 0, "question": "q", "answer": "a", "question_type": "other", '
        '"answered": false, "prompt_tokens": ' + "9" * 300 + "}]",
    ),
    "deep nesting": raw("x", "actions", "[" * 5000 + "]" * 5000),
    "nesting just under the parser's limit": raw("x", "failures", "[" * 900 + "]" * 900),
    "steps without a trace": raw("x", "steps", "9999").replace(
        '"geodesic_trace": [3.0, 2.0, 1.0, 0.1]', '"geodesic_trace": []'
    ),
    "failed actions past the steps": raw("x", "failed_actions", str(10**18)),
    "failures by kind that do not add up": raw("x", "failures", '{"parse": 3}'),
    "answers past the budget": raw(
        "x",
        "dialog",
        '[{"step": 1, "question": "q", "answer": "a", "question_type": "other", "answered": true}]',
    ),
    "a question after the last step": raw(
        "x",
        "dialog",
        '[{"step": 40, "question": "q", "answer": "a", "question_type": "refused", '
        '"answered": false}]',
    ),
    "the target seen after the last step": raw("x", "target_seen_step", "77"),
    "a lone surrogate in a text": raw("x", "object_category", '"chair\\ud800"'),
}


@pytest.mark.parametrize("kind", sorted(HOSTILE))
def test_a_hostile_line_is_skipped_and_named(tmp_path: Path, kind: str) -> None:
    path = tmp_path / "episodes.jsonl"
    good = [make_record(episode_id=f"e{i}") for i in range(2)]
    path.write_text(f"{line(good[0])}\n{HOSTILE[kind]}\n{line(good[1])}\n")
    scan = scan_records(path)
    assert scan.records == good
    (skipped,) = scan.skipped
    assert (skipped.kind, skipped.line) == ("invalid", 2)
    assert len(skipped.describe()) < 300 and "\n" not in skipped.describe()


def test_the_step_cap_of_run_json_bounds_the_steps(tmp_path: Path) -> None:
    run = RunDirectory(tmp_path / "run")
    run.prepare(EvalConfig(agent="random", task="iign", max_steps=3), planned=2)
    over = make_record(episode_id="e0")
    within = make_record(episode_id="e1", geodesic_trace=[1.0, 0.5, 0.1])
    run.episodes_path.write_text(f"{line(over)}\n{line(within)}\n")
    contents = load_runs([run.path])
    assert contents.records == [within]
    (skipped,) = contents.skipped
    assert "'steps' is 4, over the run's step cap of 3" in skipped.reason


def run_with_hostile_lines(root: Path) -> tuple[Path, list[EpisodeRecord]]:
    run = RunDirectory(root)
    run.prepare(EvalConfig(agent="random", task="iign"), planned=3)
    good = [make_record(episode_id=f"e{i}") for i in range(3)]
    lines = [line(good[0]), *HOSTILE.values(), line(good[1]), line(good[2])]
    run.episodes_path.write_text("\n".join(lines) + "\n")
    return root, good


def test_score_and_report_state_the_skipped_lines_in_one_line_each(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    root, _ = run_with_hostile_lines(tmp_path / "run")
    assert main(["score", str(root)]) == 0
    captured = capsys.readouterr()
    health = [text for text in captured.err.splitlines() if text.startswith("run health")]
    assert len(health) == 1 and f"invalid {len(HOSTILE)}" in health[0]
    assert "3 of 3 episode lines" in health[0]
    assert main(["report", str(root), "--out", str(tmp_path / "report")]) == 0
    assert (tmp_path / "report" / "report.html").is_file()


def test_a_resume_sets_the_hostile_lines_aside_and_keeps_every_valid_one(tmp_path: Path) -> None:
    root, good = run_with_hostile_lines(tmp_path / "run")
    with RunDirectory(root).writing() as writer:
        assert writer.records == good
        assert len(writer.skipped) == len(HOSTILE)
    assert scan_records(root / "episodes.jsonl").records == good
    aside = (root / SKIPPED_FILE).read_text().splitlines()
    assert aside == list(HOSTILE.values())


@pytest.mark.slow
def test_the_commands_resume_a_real_run_past_hostile_lines(
    tmp_path: Path, split_cache: Path, scenes: SceneCache, capsys: pytest.CaptureFixture[str]
) -> None:
    """The reproduction: a 5,000-digit integer and a forged step count in two lines of a
    finished run; score and report go on, the same eval command plays both episodes again."""
    run = tmp_path / "run"
    assert evaluate(run, split_cache, scenes).complete
    original = lines(run)
    hostile = [
        original[2].replace('"steps":', '"steps":' + "9" * 5000 + ',"_":', 1),
        json.dumps(json.loads(original[4]) | {"steps": 9999, "geodesic_trace": []}),
    ]
    changed = [*original[:2], hostile[0], original[3], hostile[1], *original[5:]]
    (run / "episodes.jsonl").write_text("\n".join(changed) + "\n")
    assert main(["score", str(run)]) == 0
    err = capsys.readouterr().err
    assert "INCOMPLETE, 6 of 8" in err and "invalid 2" in err and "episodes.jsonl:3" in err
    assert main(["report", str(run), "--out", str(tmp_path / "report")]) == 0
    assert main(eval_args(run, split_cache)) == 0
    assert "complete, 8 of 8" in capsys.readouterr().err
    assert sorted(lines(run)) == sorted(original)
    assert (run / SKIPPED_FILE).read_text().splitlines() == hostile
