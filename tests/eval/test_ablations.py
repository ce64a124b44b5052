"""The ablation switches of ``vlln eval``: each changes what it should and nothing else, is
stored in run.json, and ``vlln report`` tables runs that differ in one of them.

The runs play one episode of the small preset's first test house with the frontier agent:
it asks an attribute question, a route question and disambiguation questions, and one of the
objects it asks about is a same-category distractor (so cues and plain answers differ).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from tests.eval.runs import evaluate
from tests.oracle.llm.chat_server import Scripted, chat_server, completion
from vlln.cli import main
from vlln.eval.config import EvalConfig
from vlln.eval.options import ReportOptions
from vlln.eval.report import write_report
from vlln.oracle.disambiguation import PLAIN_NO
from vlln.oracle.llm.prompts import is_classification
from vlln.oracle.rule_oracle import TYPE_REFUSAL
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import load_or_build_split

pytestmark = pytest.mark.slow  # plays whole episodes or trains a model

YES = ("Yes.", "Yes, that is the one.", "Yes, this is it.")
EPISODE: dict[str, Any] = {  # the 6th of 9 episodes spread over the house: the one described above
    "agent": "frontier",
    "episodes": 9,
    "shard": "5/9",
    "budgets": (5,),
    "max_steps": 150,
}
SWITCHED: dict[str, dict[str, Any]] = {
    "plain": {"disambiguation": "plain"},
    "cues": {"disambiguation": "cues"},
    "no-route": {"disambiguation": "plain", "question_types": "attribute,disambiguation,other"},
}


@pytest.fixture(scope="module")
def runs(
    tmp_path_factory: pytest.TempPathFactory, split_cache: Path, scenes: SceneCache
) -> dict[str, Path]:
    root = tmp_path_factory.mktemp("ablations")
    for name, switch in SWITCHED.items():
        evaluate(root / name, split_cache, scenes, **EPISODE, **switch)
    return {name: root / name for name in SWITCHED}


def _records(run: Path) -> list[EpisodeRecord]:
    lines = (run / "episodes.jsonl").read_text(encoding="utf-8").splitlines()
    return [EpisodeRecord.from_json(json.loads(line)) for line in lines]


def _stored(run: Path) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((run / "run.json").read_text(encoding="utf-8"))
    return data


def _first_difference(a: EpisodeRecord, b: EpisodeRecord) -> int | None:
    """The index of the first dialog turn the two records differ in (None: none differs)."""
    for index, (mine, theirs) in enumerate(zip(a.dialog, b.dialog, strict=False)):
        if mine != theirs:
            return index
    return None


def _same_until(a: EpisodeRecord, b: EpisodeRecord, index: int) -> None:
    """The records agree on everything before turn ``index``, and on its step and question."""
    step = a.dialog[index].step
    assert a.dialog[:index] == b.dialog[:index]
    assert (a.dialog[index].step, a.dialog[index].question) == (step, b.dialog[index].question)
    assert a.positions[: step + 1] == b.positions[: step + 1]


def test_disambiguation_switch_changes_only_disambiguation_answers(runs: dict[str, Path]) -> None:
    assert _stored(runs["plain"])["disambiguation"] == "plain"
    assert _stored(runs["cues"])["disambiguation"] == "cues"
    plain, cues = _records(runs["plain"]), _records(runs["cues"])
    assert len(plain) == len(cues) == 1
    for mine, theirs in zip(plain, cues, strict=True):
        for turn in mine.dialog:
            if turn.question_type == "disambiguation":
                assert turn.answer in YES + PLAIN_NO, turn.answer
        index = _first_difference(mine, theirs)
        assert index is not None, "the episode was chosen for a distractor; its answers differ"
        _same_until(mine, theirs, index)
        assert mine.dialog[index].question_type == theirs.dialog[index].question_type
        assert mine.dialog[index].question_type == "disambiguation"
        assert mine.dialog[index].answer in PLAIN_NO
        assert theirs.dialog[index].answer.startswith("No") and theirs.dialog[index].answer not in (
            PLAIN_NO
        )


def test_a_route_question_of_a_run_without_route_gets_the_refusal(runs: dict[str, Path]) -> None:
    stored = _stored(runs["no-route"])
    assert stored["question_types"] == ["attribute", "disambiguation", "other"]
    (allowed,) = _records(runs["plain"])
    (refusing,) = _records(runs["no-route"])
    index = _first_difference(allowed, refusing)
    assert index is not None
    _same_until(allowed, refusing, index)
    assert allowed.dialog[index].question_type == "route"
    refused = refusing.dialog[index]
    assert (refused.answer, refused.question_type) == (TYPE_REFUSAL, "route")
    assert refused.answered and refused.type_refused
    routes = [turn for turn in refusing.dialog if turn.question_type == "route"]
    assert all(turn.type_refused and turn.answer == TYPE_REFUSAL for turn in routes)
    health = json.loads((runs["no-route"] / "summary.json").read_text())["health"]
    assert health["refused_questions"] == len(routes)
    summary_md = (runs["no-route"] / "summary.md").read_text()
    assert f"questions refused for their type {len(routes)}" in summary_md
    assert (
        json.loads((runs["plain"] / "summary.json").read_text())["health"]["refused_questions"] == 0
    )


def test_report_of_runs_differing_in_one_switch_draws_its_ablation_table(
    runs: dict[str, Path], tmp_path: Path
) -> None:
    write_report([runs["plain"], runs["cues"]], tmp_path / "one", ReportOptions(samples=0))
    text = (tmp_path / "one" / "report.md").read_text(encoding="utf-8")
    assert "## Ablation: disambiguation" in text
    table = text.split("## Ablation: disambiguation", 1)[1]
    header = next(line for line in table.splitlines() if line.startswith("| run"))
    assert [cell.strip() for cell in header.strip("|").split("|")][4:8] == [
        "SR", "SPL", "OS", "NE"
    ]  # fmt: skip
    rows = [
        line
        for line in table.splitlines()
        if line.startswith("| plain") or line.startswith("| cues")
    ]
    assert [row.split("|")[1].strip() for row in rows[:2]] == [
        "plain (disambiguation=plain)",
        "cues (disambiguation=cues)",
    ]
    metrics = text.split("## Metrics", 1)[1].split("##", 1)[0]
    assert "plain (disambiguation=plain): frontier" in metrics
    assert "cues (disambiguation=cues): frontier" in metrics

    every = [runs["plain"], runs["cues"], runs["no-route"]]
    write_report(every, tmp_path / "two", ReportOptions(samples=0))
    text = (tmp_path / "two" / "report.md").read_text(encoding="utf-8")
    assert "## Ablation" not in text  # two switches differ: no single ablation
    assert "no-route (question_types=attribute+disambiguation+other, disambiguation=plain)" in text


def test_run_json_replays_the_switches_and_an_old_one_reads_as_it_was_played(
    runs: dict[str, Path],
) -> None:
    replayed = EvalConfig.from_json(_stored(runs["no-route"]), "run.json")
    assert replayed.question_types == ("attribute", "disambiguation", "other")
    assert replayed.disambiguation == "plain"
    stored = _stored(runs["plain"])
    for name in ("oracle", "question_types", "disambiguation"):
        del stored[name]
    old = EvalConfig.from_json(stored, "run.json")
    assert (old.oracle, old.disambiguation) == ("rules", "cues")
    assert old.question_types == ("attribute", "route", "disambiguation", "other")


SERVER_ANSWER = "The server says: look by the window."


def _fake_model(request: dict[str, Any]) -> Scripted:
    """Classifies every question as an attribute question and answers it with one sentence."""
    prompt = str(request["json"]["messages"][0]["content"])
    return completion("attribute" if is_classification(prompt) else SERVER_ANSWER)


def test_eval_with_the_llm_oracle_plays_the_servers_dialog(
    split_cache: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    load_or_build_split("test", "iign", 1, split_cache, progress=False, preset="small")
    monkeypatch.setenv("VLLN_TEST_ORACLE_KEY", "sk-never-stored")
    out = tmp_path / "llm"
    with chat_server([], respond=_fake_model) as server:
        code = main(
            [
                "eval", "--agent", "frontier", "--task", "iign", "--preset", "small",
                "--houses", "1", "--episodes", "9", "--shard", "0/9", "--budgets", "5",
                "--max-steps", "80", "--cache-dir", str(split_cache), "--out", str(out),
                "--quiet", "--oracle", "llm", "--oracle-model", "fake",
                "--oracle-base-url", server.base_url,
                "--oracle-api-key-env", "VLLN_TEST_ORACLE_KEY",
            ]
        )  # fmt: skip
    assert code == 0
    (record,) = _records(out)
    answered = [turn for turn in record.dialog if turn.answered]
    assert answered and all(turn.answer == SERVER_ANSWER for turn in answered)
    assert all(turn.backend == "openai:fake@127.0.0.1" for turn in answered)
    assert all(turn.prompt_tokens > 0 and not turn.fallback for turn in answered)
    assert len(server.requests) == 2 * len(answered)  # classified, then worded
    assert server.requests[0]["headers"]["authorization"] == "Bearer sk-never-stored"
    stored = _stored(out)
    assert (stored["oracle"], stored["oracle_model"]) == ("llm", "fake")
    assert stored["oracle_api_key_env"] == "VLLN_TEST_ORACLE_KEY"
    assert stored["provenance"]["oracle"] == "LLMOracle"
    assert stored["provenance"]["backend"] == "openai:fake@127.0.0.1"
    for path in out.iterdir():
        if path.is_file():
            assert "sk-never-stored" not in path.read_text(encoding="utf-8"), path
