"""Navigator x oracle: who played is read from records, and the report's section on people."""

from __future__ import annotations

import json
from pathlib import Path

from vlln.eval.options import ReportOptions
from vlln.eval.pairings import cross_table, involves_people, oracle_kind
from vlln.eval.report import write_report
from vlln.tasks.record import DialogTurn, EpisodeRecord


def _record(agent: str, oracle: str | None, reached: bool, backend: str = "rules") -> EpisodeRecord:
    turn = DialogTurn(0, "What color is it?", "Red.", "attribute", True, backend=backend)
    return EpisodeRecord(
        episode_id=f"{agent}-{oracle}-{reached}",
        scene_id="vlln/house_00039",
        task="iign",
        agent=agent,
        budget=5,
        object_category="chair",
        target_ids=[3],
        end_reason="stop",
        steps=2,
        geodesic_start=4.0,
        geodesic_trace=[4.0, 0.1 if reached else 3.0],
        path_length=4.0,
        stop_instance_id=3 if reached else None,
        stop_instance_category="chair" if reached else None,
        target_seen_step=2,
        dialog=[turn],
        oracle=oracle,
    )


def test_the_oracle_comes_from_the_record_or_its_answers() -> None:
    assert oracle_kind(_record("frontier", None, True)) == "rule"
    assert oracle_kind(_record("frontier", None, True, backend="openai:gpt-4o@x")) == "LLM"
    assert oracle_kind(_record("frontier with human oracle", "human", True)) == "human"
    assert oracle_kind(_record("frontier", None, True, backend="helpful")) == "helpful"
    assert not involves_people([_record("frontier", None, True)])


def test_the_helpful_oracle_has_a_column_only_where_it_answered() -> None:
    records = [_record("human:p1", "rules", True), _record("human:p2", "helpful", False)]
    table = cross_table(records)
    assert table.header[-1] == "helpful oracle"
    assert table.rows[0][-1] == "0.0 (n=1)"
    assert "helpful oracle" not in cross_table(records[:1]).header


def test_the_cross_table_counts_each_pairing(tmp_path: Path) -> None:
    records = [
        _record("human:p1", "rules", True),
        _record("human:p2", "rules", False),
        _record("human:p1 with human oracle", "human", True),
        _record("frontier with human oracle", "human", False),
        _record("frontier", None, True),
    ]
    table = cross_table(records)
    assert table.header == ["SR % (episodes)", "human oracle", "rule oracle", "LLM oracle"]
    assert table.rows == [
        ["human navigator", "100.0 (n=1)", "50.0 (n=2)", "–"],
        ["agent navigator", "0.0 (n=1)", "100.0 (n=1)", "–"],
    ]
    run = tmp_path / "web"
    run.mkdir()
    lines = [json.dumps(record.to_json()) for record in records]
    (run / "episodes.jsonl").write_text("\n".join(lines) + "\n", encoding="utf-8")
    write_report([run], tmp_path / "report", ReportOptions(samples=0))
    text = (tmp_path / "report" / "report.md").read_text(encoding="utf-8")
    assert "## People and agents" in text and "| human navigator | 100.0 (n=1) |" in text
    assert "human navigator, rule oracle" in text
