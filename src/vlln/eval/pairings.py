"""Who navigated and who answered: people and agents on both sides of the dialog.

The paper's strongest finding is the gap between people and agents, measured with people as
navigators and as oracles. A record's navigator is a person when its agent label starts with
``human`` (the web app's ``human:<participant>``); its oracle is the record's ``oracle`` field
(rules, llm, human, helpful) or, for records without one (``vlln eval``), read from the
backends of its answered turns: the rule oracle unless a language model or the helpful
oracle answered.
"""

from __future__ import annotations

from collections.abc import Sequence

from vlln.eval.document import Block, Heading, Paragraph, Table
from vlln.tasks.aggregate import format_table, summarize
from vlln.tasks.metrics import SUCCESS_RADIUS, success
from vlln.tasks.record import EpisodeRecord

NAVIGATORS = ("human", "agent")
ORACLES = ("human", "rule", "LLM")
_ORACLE_NAMES = {"rules": "rule", "llm": "LLM", "human": "human", "helpful": "helpful"}


def navigator_kind(record: EpisodeRecord) -> str:
    return "human" if record.agent.startswith("human") else "agent"


def oracle_kind(record: EpisodeRecord) -> str:
    """``human``, ``rule``, ``LLM`` or ``helpful``; ``none`` for an episode without dialog."""
    if record.budget == 0:
        return "none"
    if record.oracle is not None:
        return _ORACLE_NAMES.get(record.oracle, record.oracle)
    backends = {turn.backend for turn in record.dialog if turn.answered}
    if "human" in backends:
        return "human"
    if "helpful" in backends:
        return "helpful"
    return "LLM" if backends - {"rules"} else "rule"


def involves_people(records: Sequence[EpisodeRecord]) -> bool:
    return any(navigator_kind(r) == "human" or oracle_kind(r) == "human" for r in records)


def cross_table(records: Sequence[EpisodeRecord], success_radius: float = SUCCESS_RADIUS) -> Table:
    """SR (and episode count) per navigator kind and oracle kind; ``–`` where none played.
    The helpful oracle, this benchmark's extension, has a column only where it answered."""
    helpful = any(oracle_kind(record) == "helpful" for record in records)
    oracles = (*ORACLES, "helpful") if helpful else ORACLES
    rows = []
    for navigator in NAVIGATORS:
        row = [f"{navigator} navigator"]
        for oracle in oracles:
            cell = [
                r for r in records if navigator_kind(r) == navigator and oracle_kind(r) == oracle
            ]
            wins = sum(success(r, success_radius) for r in cell)
            row.append(f"{100.0 * wins / len(cell):.1f} (n={len(cell)})" if cell else "–")
        rows.append(row)
    return Table(["SR % (episodes)", *(f"{oracle} oracle" for oracle in oracles)], rows)


def people_section(
    records: Sequence[EpisodeRecord], success_radius: float, os_radius: float
) -> list[Block]:
    """The report's section on people: every metric per pairing, then the cross table."""
    if not involves_people(records):
        return []
    groups: dict[str, list[EpisodeRecord]] = {}
    for record in sorted(records, key=lambda r: (navigator_kind(r), oracle_kind(r))):
        key = f"{navigator_kind(record)} navigator, {oracle_kind(record)} oracle"
        groups.setdefault(key, []).append(record)
    rows = {name: summarize(group, success_radius, os_radius) for name, group in groups.items()}
    table, notes = Table.from_markdown(format_table(rows))
    return [
        Heading(2, "People and agents"),
        Paragraph(
            "Episodes grouped by who navigated (a person in the browser, or an agent) and who "
            "answered the questions (a person, the rule oracle or a language model), over "
            "all budgets of these runs."
        ),
        table,
        *(Paragraph(note) for note in notes),
        cross_table(records, success_radius),
    ]
