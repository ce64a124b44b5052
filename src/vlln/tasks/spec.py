"""What a task is: its type, its caps and budgets, and the actions an agent may return."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Literal

from vlln.errors import ConfigError
from vlln.sim.agent import Action

REFUSAL_MESSAGE = "Sorry, you have reached the question limit. No further answers are available."


class TaskType(StrEnum):
    """IIGN: category-only instruction plus dialog; IGN: full description, no dialog;
    ObjectNav: any instance of the category is a goal."""

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


@dataclass(frozen=True)
class TaskConfig:
    """Caps and budgets (reference-facts §1). STOP, FORWARD and TURN count toward
    ``max_steps``; LOOK and TALK do not, so they have caps of their own; outputs that are
    neither an Action nor a Talk are failed actions, recorded, and capped too."""

    task: TaskType = TaskType.IIGN
    max_steps: int = 500
    max_look_actions: int = 100
    max_talk_actions: int = 20
    max_failed_actions: int = 20
    dialog_budget: int = 5
    success_radius: float = 0.25

    def __post_init__(self) -> None:
        for name in ("max_steps", "max_look_actions", "max_talk_actions", "max_failed_actions"):
            if getattr(self, name) < 1:
                raise ConfigError(f"{name} must be at least 1, got {getattr(self, name)}")
        if self.dialog_budget < 0:
            raise ConfigError(f"dialog_budget must be >= 0, got {self.dialog_budget}")
        if not self.success_radius > 0:
            raise ConfigError(f"success_radius must be positive, got {self.success_radius}")

    @property
    def dialog_enabled(self) -> bool:
        return self.task == TaskType.IIGN and self.dialog_budget > 0
