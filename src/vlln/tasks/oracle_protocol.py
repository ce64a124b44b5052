"""The oracle protocol the environment calls: start an episode with privileged context, answer
questions. It lives in tasks, the layer that calls it; the answerers (vlln.oracle) implement it."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Protocol

from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.world.model import ObjectInstance


class QuestionType(StrEnum):
    ATTRIBUTE = "attribute"
    ROUTE = "route"
    DISAMBIGUATION = "disambiguation"
    OTHER = "other"


@dataclass(frozen=True)
class EpisodeContext:
    """What the oracle knows for one episode: the house (through the simulator), the target
    and its goal view points."""

    simulator: Simulator
    target: ObjectInstance
    view_points: tuple[tuple[float, ...], ...]  # (x, z), or (x, y, z) on several storeys


@dataclass(frozen=True)
class Question:
    """A question with the asker's state and current view (for "is this the one?"), and the
    positions (x, y, z) it has stood at so far, oldest first and ending where it stands (empty
    where the caller keeps no history), so that an answer can say whether it is getting
    closer or has passed the target."""

    text: str
    state: AgentState
    frame: Frame
    path: tuple[tuple[float, float, float], ...] = ()


@dataclass(frozen=True)
class Reply:
    """An answer and how it was made: by which backend, how long the model took, the tokens
    it spent, whether offline logic stood in for a model call that failed, and whether the
    question was refused for its type (the run does not allow questions of that type), and
    which kind of help it gave (empty from the paper's oracles; see docs/helpful-oracle.md)."""

    answer: str
    question_type: QuestionType
    backend: str = "rules"
    latency_ms: float = 0.0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    fallback: bool = False
    type_refused: bool = False
    help_kind: str = ""


class Oracle(Protocol):
    """Answers questions about one episode at a time."""

    def start(self, context: EpisodeContext) -> None: ...

    def answer(self, question: Question) -> Reply: ...
