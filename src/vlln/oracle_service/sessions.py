"""Dialog sessions of the oracle service and the bounded store that keeps them.

A session is one target with its dialog budget, the oracle that answers (the rule or the
helpful oracle) and its turns. The oracle (which holds the house's look-ups and a distance
field) lives only while the session's simulator is in the scene cache; once the cache drops
that house, the oracle is dropped too and rebuilt on the next question (replaying the
answered turns, so the wording stays that of the seed). So
memory is bounded by the scene cache, not by the number of sessions. The store keeps at
most ``capacity`` sessions and drops the least recently used one when a new one would exceed
it, so a client that never deletes its sessions cannot grow the server's memory without bound.
A session's dialog keeps every answered turn (at most the budget) and the first
:data:`REFUSED_TURNS_KEPT` refused ones; later refusals are only counted, so a client asking
on past its budget cannot grow a session, or the reply that shows it, without bound.
Session ids are unguessable (:func:`secrets.token_urlsafe`) because they are the only handle
on a dialog; they name a session and never influence an answer, so determinism is unaffected.
"""

from __future__ import annotations

import secrets
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field

from vlln.errors import ConfigError
from vlln.http.responses import RequestError
from vlln.oracle_service.schemas import DialogTurnView, OracleName
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import GoalPoint
from vlln.tasks.oracle_protocol import Oracle
from vlln.world.model import ObjectInstance


class ServiceError(RequestError):
    """A request the oracle service cannot serve; ``status`` is its HTTP status code."""


REFUSED_TURNS_KEPT = 8


def new_session_id() -> str:
    """128 random bits, URL-safe."""
    return secrets.token_urlsafe(16)


@dataclass
class Session:
    """One dialog: the target, its oracle, the budget and the turns so far."""

    session_id: str
    scene_id: str
    episode_id: str | None
    target: ObjectInstance
    goals: tuple[GoalPoint, ...]  # (x, z), or (x, y, z) in a house with several storeys
    instruction: str | None
    dialog_budget: int
    oracle_name: OracleName = "rules"  # which oracle answers: the rule or the helpful oracle
    oracle: Oracle | None = None  # started on ``simulator``; None once that is dropped
    simulator: Simulator | None = None
    dialog: list[DialogTurnView] = field(default_factory=list)
    answered: int = 0
    refused: int = 0  # questions asked past the budget, kept or not

    @property
    def questions_left(self) -> int:
        return max(0, self.dialog_budget - self.answered)


class SessionStore:
    """Sessions by id, least recently used dropped first once ``capacity`` is reached; safe to
    use from the event loop and the worker thread at once."""

    def __init__(self, capacity: int, new_id: Callable[[], str] = new_session_id) -> None:
        if isinstance(capacity, bool) or not isinstance(capacity, int) or capacity < 1:
            raise ConfigError(f"the session store needs a capacity >= 1, got {capacity!r}")
        self.capacity = capacity
        self._new_id = new_id
        self._sessions: OrderedDict[str, Session] = OrderedDict()
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._sessions)

    def fresh_id(self) -> str:
        """An id no stored session has."""
        while True:
            session_id = self._new_id()
            if session_id not in self._sessions:
                return session_id

    def add(self, session: Session) -> None:
        with self._lock:
            if session.session_id in self._sessions:
                raise ConfigError(f"a session with id {session.session_id!r} is already stored")
            self._sessions[session.session_id] = session
            while len(self._sessions) > self.capacity:
                self._sessions.popitem(last=False)

    def get(self, session_id: str) -> Session:
        """The session, marked as most recently used; 404 when it is unknown or was dropped."""
        with self._lock:
            session = self._sessions.get(session_id)
            if session is not None:
                self._sessions.move_to_end(session_id)
        if session is None:
            raise ServiceError(
                404,
                "unknown session",
                f"no session {session_id[:64]!r}; it was deleted, dropped as least recently used "
                f"(at most {self.capacity} are kept), or never created: POST /v1/sessions",
            )
        return session

    def sessions(self) -> list[Session]:
        with self._lock:
            return list(self._sessions.values())

    def remove(self, session_id: str) -> None:
        self.get(session_id)
        with self._lock:
            self._sessions.pop(session_id, None)
