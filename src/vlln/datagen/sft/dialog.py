"""The questions of a trajectory as the model will hear them back, dialog budget applied."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from vlln.tasks.spec import REFUSAL_MESSAGE


@dataclass(frozen=True)
class DialogExchange:
    """A question asked at ``frame`` and the answer the navigator got."""

    frame: int
    question: str
    answer: str
    refused: bool = False  # the budget was spent: ``answer`` is the refusal message


def apply_budget(exchanges: Sequence[DialogExchange], budget: int | None) -> list[DialogExchange]:
    """Exchanges in asking order; those after the first ``budget`` get the benchmark's refusal
    instead of the oracle's answer (None = no budget)."""
    ordered = sorted(exchanges, key=lambda exchange: exchange.frame)  # stable: asking order
    return [
        DialogExchange(e.frame, e.question, REFUSAL_MESSAGE, True)
        if budget is not None and number >= budget
        else e
        for number, e in enumerate(ordered)
    ]
