"""The default step limit and the dialog-budget rule are stated once, in vlln.tasks.spec.

Every ``max_steps`` (a field, a parameter, a keyword) takes its default from
``DEFAULT_MAX_STEPS``, and every check of a budget goes through ``TaskType.check_budget``: a
second literal limit or a second comparison against ``MAX_DIALOG_BUDGET`` fails here."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from vlln.errors import ConfigError
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskType

SRC = Path(__file__).resolve().parents[2] / "src" / "vlln"
SPEC = SRC / "tasks" / "spec.py"
STEP_LIMITS = ("max_steps", "max_look_actions")


def _literal_int(node: ast.AST | None) -> bool:
    return isinstance(node, ast.Constant) and type(node.value) is int


def second_statements(source: str) -> list[str]:
    """Lines of ``source`` that state a step limit as a number or compare a budget with the
    largest budget themselves."""
    found: list[str] = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.AnnAssign | ast.Assign):
            targets = [node.target] if isinstance(node, ast.AnnAssign) else node.targets
            names = [t.id if isinstance(t, ast.Name) else getattr(t, "attr", "") for t in targets]
            if any(name in STEP_LIMITS for name in names) and _literal_int(node.value):
                found.append(f"line {node.lineno}: {names[0]} = a number")
        elif isinstance(node, ast.arguments):
            positional = [*node.posonlyargs, *node.args]
            with_defaults = positional[len(positional) - len(node.defaults) :]
            pairs = list(zip(with_defaults, node.defaults, strict=True))
            pairs += [
                (a, d)
                for a, d in zip(node.kwonlyargs, node.kw_defaults, strict=True)
                if d is not None
            ]
            found += [
                f"line {arg.lineno}: parameter {arg.arg} defaults to a number"
                for arg, default in pairs
                if arg.arg in STEP_LIMITS and _literal_int(default)
            ]
        elif isinstance(node, ast.Compare):
            names = {n.id for n in ast.walk(node) if isinstance(n, ast.Name)}
            if "MAX_DIALOG_BUDGET" in names:
                found.append(f"line {node.lineno}: a budget compared with MAX_DIALOG_BUDGET")
    return found


def test_the_step_limit_and_the_budget_rule_are_stated_once() -> None:
    found = {
        str(path.relative_to(SRC)): lines
        for path in sorted(SRC.rglob("*.py"))
        if path != SPEC and (lines := second_statements(path.read_text(encoding="utf-8")))
    }
    assert found == {}
    assert second_statements(SPEC.read_text(encoding="utf-8"))  # the one place is seen


def test_the_check_sees_each_kind_of_second_statement() -> None:
    source = (
        "class A:\n    max_steps: int = 500\n"
        "def f(max_steps=400, *, max_look_actions=9): pass\n"
        "def g(budget): return budget > MAX_DIALOG_BUDGET\n"
    )
    assert second_statements(source) == [
        "line 2: max_steps = a number",
        "line 3: parameter max_steps defaults to a number",
        "line 3: parameter max_look_actions defaults to a number",
        "line 4: a budget compared with MAX_DIALOG_BUDGET",
    ]


@pytest.mark.parametrize(
    ("task", "budget", "message"),
    [
        (TaskType.IIGN, 6, "0 to 5"),
        (TaskType.IGN, -1, "0 to 5"),
        (TaskType.OBJECTNAV, 1, "objectnav has no dialog"),
    ],
)
def test_one_budget_rule_for_eval_the_web_app_gym_and_the_service(
    task: TaskType, budget: int, message: str
) -> None:
    import gymnasium
    from pydantic import ValidationError

    from vlln.eval.config import EvalConfig
    from vlln.oracle_service.schemas import CreateSessionRequest
    from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
    from vlln.web.config import WebConfig

    goal = Goal((1.0, 0.0, 1.0), None, None, (ViewPoint((1.0, 0.0, 0.5)),))
    instruction = Instruction(task.value, "Search for the chair.", ("1",))
    episode = Episode(
        "e", "vlln/house_00076", (0.0, 0.0, 0.0), (0, 0, 0, 1), "chair", (goal,), instruction
    )

    with pytest.raises(ConfigError, match=message):
        task.check_budget(budget)
    with pytest.raises(ConfigError, match=message):
        EvalConfig(agent="random", task=task.value, budgets=(budget,))
    with pytest.raises(ConfigError, match=message):
        WebConfig(task=task, dialog_budget=budget, episodes=(episode,), out=Path("unused"))
    with pytest.raises(ConfigError, match=message):
        gymnasium.make(
            "vlln.gym:vlln/IIGN-v0", task=task.value, dialog_budget=budget, preset="small"
        )
    if budget > 5:
        with pytest.raises(ValidationError, match="less than or equal to 5"):
            CreateSessionRequest(episode_id="e", dialog_budget=budget)


def test_every_step_limit_defaults_to_the_reference_cap() -> None:
    import gymnasium

    from vlln.datagen.collector.collect import CollectorConfig
    from vlln.eval.config import EvalConfig
    from vlln.web.config import WebLimits

    env = gymnasium.make("vlln.gym:vlln/IIGN-v0", preset="small").unwrapped
    limits = [
        EvalConfig(agent="random", task="iign").max_steps,
        WebLimits().max_steps,
        CollectorConfig().max_steps,
        env.config.max_steps,  # type: ignore[attr-defined]
    ]
    assert DEFAULT_MAX_STEPS == 500 and limits == [DEFAULT_MAX_STEPS] * 4
