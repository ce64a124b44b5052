"""Ablation switches of a run and the ablation table of ``vlln report``.

A switch is a setting of ``vlln eval`` that one of the paper's ablations varies while
keeping everything else fixed: the oracle's backbone (``oracle``: rules, or llm with its
model), the question types it answers (``question_types``) and how it answers
disambiguation questions (``disambiguation``). Runs compared in one report are named by the
switches in which they differ; when they differ in exactly one, the report draws the table
of that ablation, one row per value.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from vlln.eval.config import EvalConfig
from vlln.eval.document import Block, Heading, Paragraph, Table
from vlln.eval.summary import GroupSummary
from vlln.oracle.rule_oracle import ALL_QUESTION_TYPES

SWITCHES = ("oracle", "question_types", "disambiguation")
"""The switches, in the order a row names them."""


def switch_values(config: EvalConfig) -> dict[str, str]:
    """Each switch's value as a row shows it: ``oracle=llm:gpt-4o`` (``helpful:gpt-4o`` for
    the helpful oracle worded by that model), ``question_types=attribute+route`` (``all`` for
    the four), ``disambiguation=plain``."""
    oracle = (
        config.oracle if config.oracle_model is None else f"{config.oracle}:{config.oracle_model}"
    )
    every = tuple(kind.value for kind in ALL_QUESTION_TYPES)
    types = "all" if config.question_types == every else "+".join(config.question_types)
    return {"oracle": oracle, "question_types": types, "disambiguation": config.disambiguation}


def differing_switches(configs: Sequence[EvalConfig | None]) -> list[str]:
    """The switches whose values differ between the runs whose settings are known."""
    values = [switch_values(config) for config in configs if config is not None]
    return [name for name in SWITCHES if len({value[name] for value in values}) > 1]


def switch_label(config: EvalConfig | None, names: Sequence[str]) -> str:
    """``name=value, ...`` of the switches ``names`` for one run ("" when none or unknown)."""
    if config is None or not names:
        return ""
    values = switch_values(config)
    return ", ".join(f"{name}={values[name]}" for name in names)


PAPER_ABLATIONS = {
    "oracle": "the oracle-backbone ablation (paper supplementary, Oracle-Backbone Ablation)",
    "question_types": "the question-type ablation (paper supplementary, Question-Type Ablation)",
    "disambiguation": "plain is the paper's yes/no answer; cues is this benchmark's extension",
}


def ablation_section(switch: str, runs: Sequence[tuple[str, list[GroupSummary]]]) -> list[Block]:
    """The table of an ablation of ``switch``: one row per run (its label names the value)
    and agent, at the run's largest budget, with MSP where the run swept budgets 0..n."""
    header = ["run", "agent on task", "budget", "episodes", "SR", "SPL", "OS", "NE", "MSP"]
    rows = []
    for label, groups in runs:
        for group in groups:
            budget = max(group.sweep.by_budget)
            summary = group.sweep.by_budget[budget]
            msp = group.sweep.msp
            rows.append(
                [
                    label,
                    group.label,
                    str(budget),
                    str(summary.n),
                    f"{summary.sr:.1f}",
                    f"{summary.spl:.2f}",
                    f"{summary.os:.1f}",
                    "-" if math.isnan(summary.ne) else f"{summary.ne:.2f}",
                    "-" if msp is None else f"{msp:.2f}",
                ]
            )
    return [
        Heading(2, f"Ablation: {switch}"),
        Paragraph(
            f"The runs differ in one switch, {switch}: {PAPER_ABLATIONS[switch]}. SR, SPL and "
            "OS in %, NE in m; MSP only where a run played every budget from 0 up."
        ),
        Table(header, rows),
    ]
