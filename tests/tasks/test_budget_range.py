"""Dialog budgets follow the paper's range, 0 to 5, wherever a task is configured."""

from __future__ import annotations

import pytest

from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig, parse_budgets
from vlln.tasks.spec import MAX_DIALOG_BUDGET, TaskConfig, TaskType


def test_the_paper_budgets_are_accepted() -> None:
    assert MAX_DIALOG_BUDGET == 5
    assert parse_budgets("0-5") == (0, 1, 2, 3, 4, 5)
    assert EvalConfig(agent="random", task="iign", budgets=(0, 5)).budgets == (0, 5)
    assert TaskConfig(TaskType.IIGN, dialog_budget=5).dialog_budget == 5


@pytest.mark.parametrize("budget", [6, 7, 10**18])
def test_a_budget_past_five_is_refused_everywhere(budget: int) -> None:
    with pytest.raises(ConfigError, match="0 to 5"):
        parse_budgets(f"0-{budget}")
    with pytest.raises(ConfigError, match="0 to 5"):
        EvalConfig(agent="random", task="iign", budgets=(0, budget))
    with pytest.raises(ConfigError, match="0 to 5"):
        TaskConfig(TaskType.IIGN, dialog_budget=budget)
