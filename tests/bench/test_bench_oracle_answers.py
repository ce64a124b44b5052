"""Asking a question file in real episodes: each question goes to an episode of its category,
after exploring, and the same seed gives the same answers."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from vlln.bench.oracle_answers import answer_questions, matching_episodes
from vlln.cli import main
from vlln.oracle.settings import OracleBackend
from vlln.tasks.split_files import load_or_build_split


@pytest.mark.slow
def test_questions_are_asked_in_episodes_of_their_category(
    split_cache: Path, tmp_path: Path
) -> None:
    episodes = load_or_build_split("test", "iign", 1, split_cache, progress=False)
    category = str(episodes[0].object_category)
    questions = [
        {"question": f"How many {category}s are there?", "kind": "count", "category": category},
        {"question": "tell me a joke", "kind": "unanswerable", "category": "no such thing"},
    ]
    rows = answer_questions(questions, OracleBackend.HELPFUL, episodes, seed=3)
    assert [row["question"] for row in rows] == [q["question"] for q in questions]
    assert rows[0]["target_category"] == category
    assert rows[0]["help_kind"] == "count" and "There " in rows[0]["answer"]
    assert rows[1]["answer"] == "Sorry, I cannot answer your question now."
    assert all(0 <= row["steps_walked"] <= 60 for row in rows)
    assert answer_questions(questions, OracleBackend.HELPFUL, episodes, seed=3) == rows

    source = tmp_path / "questions.jsonl"
    source.write_text("".join(json.dumps(q) + "\n" for q in questions))
    out = tmp_path / "answers.jsonl"
    args = ["bench", "oracle-answers", str(source), "--oracle", "rules", "--out", str(out)]
    assert main([*args, "--houses", "1", "--cache-dir", str(split_cache)]) == 0
    lines = [json.loads(line) for line in out.read_text().splitlines()]
    assert [line["help_kind"] for line in lines] == ["", ""]  # the paper's oracle gives none


def test_a_line_that_is_not_a_question_is_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = tmp_path / "questions.jsonl"
    source.write_text('{"question": "Is it red?", "category": "chair"}\n{"question": "hi"}\n')
    assert main(["bench", "oracle-answers", str(source), "--out", str(tmp_path / "a")]) == 2
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and f"{source}:2 is not a question line" in error


def test_a_category_by_another_name_finds_its_episodes(split_cache: Path) -> None:
    episodes = load_or_build_split("test", "iign", 1, split_cache, progress=False)
    category = str(episodes[0].object_category)
    assert all(e.object_category == category for e in matching_episodes(episodes, category))
    assert matching_episodes(episodes, "no such thing") == episodes
