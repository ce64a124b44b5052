"""What a task is: its type, its caps and budgets, and the actions an agent may return."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Literal, Self

from pydantic import model_validator

from vlln.config import Count, Positive, settings_dataclass
from vlln.errors import ConfigError
from vlln.sim.agent import Action

MAX_DIALOG_BUDGET = 5
"""The largest dialog budget. The paper's budgets run 0..5 (its MSP averages budgets 1..5) and
its dialog-turn ablation lists 5 as "∞ (5)": agents ask under two questions even then, and an
episode may talk at most ``max_talk_actions`` (20) times, so a larger budget only repeats 5."""

DEFAULT_MAX_STEPS = 500
"""Counted steps (STOP, FORWARD, TURN) before an episode is cut: the reference's cap
(docs/reference-facts.md §1). Every setting of a step limit defaults to this one."""

REFUSAL_MESSAGE = "Sorry, you have reached the question limit. No further answers are available."


class TaskType(StrEnum):
    """IIGN: category-only instruction plus dialog; IGN: full description (dialog optional);
    ObjectNav: any instance of the category is a goal (no dialog)."""

    IIGN = "iign"
    IGN = "ign"
    OBJECTNAV = "objectnav"

    @staticmethod
    def parse(name: str) -> TaskType:
        try:
            return TaskType(name.lower())
        except ValueError:
            valid = ", ".join(t.value for t in TaskType)
            raise ConfigError(f"unknown task {name!r}; choose one of: {valid}") from None

    @property
    def has_dialog(self) -> bool:
        """IIGN and IGN may talk to the oracle (the paper runs its agents with dialog on IGN
        too); ObjectNav may not: any instance is a goal, so no one object is to be described."""
        return self != TaskType.OBJECTNAV

    @property
    def default_budget(self) -> int:
        """Answered questions when none is given: the reference's 5 on IIGN, else none."""
        return 5 if self == TaskType.IIGN else 0

    def check_budget(self, budget: int) -> None:
        """The one budget rule: 0 to :data:`MAX_DIALOG_BUDGET` answered questions, and 0 on a
        task without dialog."""
        if not 0 <= budget <= MAX_DIALOG_BUDGET:
            raise ConfigError(
                f"dialog budgets run from 0 to {MAX_DIALOG_BUDGET}, the paper's range (its "
                f"budget 5 already lets an agent ask all it wants), got {budget}"
            )
        if budget > 0 and not self.has_dialog:
            raise ConfigError(
                f"task {self.value} has no dialog, so its only budget is 0 (got {budget}); "
                "use budget 0, or task iign or ign"
            )


@dataclass(frozen=True)
class Talk:
    """The TALK action: a question for the oracle."""

    text: str


@dataclass(frozen=True)
class PixelGoal:
    """A point to walk to, chosen as pixel ``(col, row)`` of the current look-down frame.

    The environment back-projects it with the frame's depth and the camera tilt, snaps it to
    the navigable area, levels the camera and offers the next step toward it in the
    observation (``waypoint_action``)."""

    col: int
    row: int


FailureKind = Literal["parse", "server"]


@dataclass(frozen=True)
class FailedOutput:
    """A decision the agent could not make: its model's output was unreadable (``parse``) or
    the model server gave none (``server``). It wastes one step, counts toward the failed-action
    cap and is recorded with its kind; it is never turned into a move or a STOP."""

    kind: FailureKind
    detail: str = ""


AgentOutput = Action | Talk | PixelGoal | FailedOutput


@settings_dataclass
class TaskConfig:
    """Caps and budgets (docs/reference-facts.md §1). STOP, FORWARD and TURN count toward
    ``max_steps``; LOOK and TALK do not, so they have caps of their own; outputs that are
    neither an Action nor a Talk are failed actions, recorded, and capped too. A model agent
    looks down once per pixel goal and a goal may be a step or two away, so the look cap
    equals the step cap: it stops endless looking, not ordinary pixel-goal navigation.
    ``dialog_budget`` left at None becomes the task's :attr:`TaskType.default_budget`."""

    task: TaskType = TaskType.IIGN
    max_steps: Count = DEFAULT_MAX_STEPS
    max_look_actions: Count = DEFAULT_MAX_STEPS
    max_talk_actions: Count = 20
    max_failed_actions: Count = 20
    dialog_budget: int = None  # type: ignore[assignment]  # None: the task's default
    success_radius: Positive = 0.25

    @model_validator(mode="after")
    def _budget_of_the_task(self) -> Self:
        if self.dialog_budget is None:
            object.__setattr__(self, "dialog_budget", self.task.default_budget)
        self.task.check_budget(self.dialog_budget)
        return self

    @property
    def dialog_enabled(self) -> bool:
        return self.task.has_dialog and self.dialog_budget > 0
