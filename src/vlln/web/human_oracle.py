"""A person as the oracle: the question goes on a board that the oracle page reads, and the
answer comes back from the browser within a time limit.

:class:`HumanOracle` implements :class:`vlln.tasks.oracle_protocol.Oracle`, so any navigator (a
person or an agent playing through :class:`vlln.tasks.env.NavigationEnv`) can be paired with
it: ``answer`` blocks the navigator's thread until the answer arrives. When no answer comes in
time, the rule oracle answers instead and the turn is recorded as a fallback, as the language-
model oracle records a failed call.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

from vlln.oracle.classify import classify_question
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.tasks.oracle_protocol import EpisodeContext, Question, Reply

HUMAN_BACKEND = "human"


@dataclass(frozen=True)
class PendingQuestion:
    """A question waiting for the person: what was asked, from where, and until when."""

    number: int  # 1 for the episode's first question
    text: str
    state: AgentState
    frame: Frame
    deadline: float  # time.monotonic() by which the answer must come

    def seconds_left(self) -> float:
        return max(0.0, self.deadline - time.monotonic())


class AnswerBoard:
    """Where one session's questions wait for a person's answer; thread-safe.

    ``on_change`` is called (from whichever thread changed it) when a question appears or is
    answered, so pages waiting for news can be woken.
    """

    def __init__(self, on_change: Callable[[], None] = lambda: None) -> None:
        self._on_change = on_change
        self._lock = threading.Lock()
        self._answered = threading.Event()
        self._pending: PendingQuestion | None = None
        self._answer: str | None = None
        self._asked = 0
        self._closed = False

    def pending(self) -> PendingQuestion | None:
        with self._lock:
            return self._pending

    def ask(self, question: Question, time_limit_s: float) -> str | None:
        """Post ``question`` and wait for the answer; None when the time limit passed."""
        with self._lock:
            if self._closed:
                return None
            self._asked += 1
            self._answer = None
            self._answered.clear()
            self._pending = PendingQuestion(
                self._asked,
                question.text,
                question.state,
                question.frame,
                time.monotonic() + time_limit_s,
            )
        self._on_change()
        self._answered.wait(time_limit_s)
        with self._lock:
            answer, self._answer, self._pending = self._answer, None, None
        self._on_change()
        return answer

    def give_up(self) -> None:
        """Stop waiting, now and for later questions (the server is shutting down)."""
        with self._lock:
            self._closed = True
            self._answered.set()

    def give(self, number: int, answer: str) -> bool:
        """Answer question ``number``; False when it is no longer waiting (answered or late)."""
        with self._lock:
            pending = self._pending
            if pending is None or pending.number != number or self._answered.is_set():
                return False
            self._answer = answer
            self._answered.set()
        return True


class HumanOracle:
    """An Oracle whose answers are typed by a person on the oracle page (module doc)."""

    def __init__(self, board: AnswerBoard, time_limit_s: float, seed: int = 0) -> None:
        self.board = board
        self.time_limit_s = time_limit_s
        self.fallback = RuleOracle(seed)

    def start(self, context: EpisodeContext) -> None:
        self.fallback.start(context)

    def answer(self, question: Question) -> Reply:
        started = time.perf_counter()
        text = self.board.ask(question, self.time_limit_s)
        waited_ms = 1000.0 * (time.perf_counter() - started)
        if text is None:
            stand_in = self.fallback.answer(question)
            return replace(stand_in, backend=HUMAN_BACKEND, latency_ms=waited_ms, fallback=True)
        return Reply(text, classify_question(question.text), HUMAN_BACKEND, waited_ms)
