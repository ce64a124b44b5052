"""When the frontier agent asks: a pluggable dialog policy consulted at decision points.

The agent navigates by itself; at a few points it hands the choice "walk on, or ask one of
the question kinds?" to a :class:`DialogPolicy`, with its belief as a small vector of
numbers in [0, 1] (:data:`FEATURES`). The points are

* ``start``: the first step the dialog is open;
* ``explore``: every ``explore_every`` exploration steps without a candidate, and whenever
  it is stuck, while a question is left beyond the one kept for "is this the one?";
* ``candidate``: once per candidate, when it comes within asking distance unconfirmed.

:class:`FixedTriggers`, the default, is the hand-set rule the agent always had (the colour at
the start, the way every ``route_after`` steps or when stuck, "is this the one?" at every
candidate), so an agent without a policy plays exactly as before. A question kind that is not
allowed at a point (:attr:`Decision.allowed`) counts as walking on.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

KINDS: tuple[str, ...] = ("attribute", "route", "disambiguation")
"""The question kinds, in the order of a policy's actions 1, 2, 3 (0 is walking on)."""
ACTIONS: tuple[str | None, ...] = (None, *KINDS)
ACTION_NAMES: tuple[str, ...] = ("walk_on", *KINDS)


class Point(StrEnum):
    """Where in the episode the policy is consulted."""

    START = "start"
    EXPLORE = "explore"
    CANDIDATE = "candidate"


FEATURES: tuple[str, ...] = (
    "budget_left",  # questions left / questions planned with
    "steps",  # counted steps / the episode's cap
    "at_start",
    "at_explore",
    "at_candidate",
    "colour_known",  # from the instruction or an answer
    "attribute_asked",
    "known_attributes",  # attributes known of the target / 3, at most 1
    "candidates_seen",  # instances of the category seen / 5, at most 1
    "fitting_seen",  # whether one that fits what is known is seen, not rejected
    "fitting_distance",  # metres to the nearest fitting one / 10, at most 1 (1: none)
    "rejected",  # candidates the oracle said no to / 3, at most 1
    "confirmed",  # whether the oracle said yes to one
    "explore_steps",  # exploration steps since the last candidate or question / 100, at most 1
    "explored",  # square metres mapped on every storey / 200, at most 1
    "stuck",
    "storeys",  # storeys visited beyond the first / 2, at most 1
    "hinted",  # whether a route answer still steers the exploration
)


@dataclass(frozen=True)
class Belief:
    """What the agent knows at a decision point, in natural units."""

    budget_left: float
    steps: float
    colour_known: bool
    attribute_asked: bool
    known_attributes: int
    candidates_seen: int
    fitting_distance: float | None  # None: no fitting candidate seen
    rejected: int
    confirmed: bool
    explore_steps: int
    explored_m2: float
    stuck: bool
    storeys: int
    hinted: bool


@dataclass(frozen=True)
class Decision:
    """One consultation: the point, what may be asked there and the belief."""

    point: Point
    allowed: tuple[str, ...]
    belief: Belief

    def features(self) -> NDArray[np.float32]:
        """The belief as the vector a learned policy reads (:data:`FEATURES` order)."""
        b = self.belief
        distance = 1.0 if b.fitting_distance is None else min(b.fitting_distance / 10.0, 1.0)
        values = (
            b.budget_left,
            b.steps,
            self.point == Point.START,
            self.point == Point.EXPLORE,
            self.point == Point.CANDIDATE,
            b.colour_known,
            b.attribute_asked,
            min(b.known_attributes / 3.0, 1.0),
            min(b.candidates_seen / 5.0, 1.0),
            b.fitting_distance is not None,
            distance,
            min(b.rejected / 3.0, 1.0),
            b.confirmed,
            min(b.explore_steps / 100.0, 1.0),
            min(b.explored_m2 / 200.0, 1.0),
            b.stuck,
            min(max(b.storeys - 1, 0) / 2.0, 1.0),
            b.hinted,
        )
        return np.clip(np.asarray(values, np.float32), 0.0, 1.0)

    def action(self, index: int) -> str | None:
        """The question kind of action ``index``; walking on (None) when not allowed here."""
        kind = ACTIONS[index]
        return kind if kind in self.allowed else None


class DialogPolicy(Protocol):
    """Chooses, at a decision point, a question kind to ask or None to walk on."""

    @property
    def explore_every(self) -> int:
        """Exploration steps without a candidate between two ``explore`` points."""

    def choose(self, decision: Decision) -> str | None:
        """The question kind to ask now (one of ``decision.allowed``), or None."""


_OWN_KIND = {Point.START: "attribute", Point.EXPLORE: "route", Point.CANDIDATE: "disambiguation"}


class FixedTriggers:
    """The hand-set rule: every point asks its own kind (colour, the way, "is this it?")."""

    def __init__(self, route_after: int) -> None:
        self._every = route_after

    @property
    def explore_every(self) -> int:
        return self._every

    def choose(self, decision: Decision) -> str | None:
        kind = _OWN_KIND[decision.point]
        return kind if kind in decision.allowed else None
