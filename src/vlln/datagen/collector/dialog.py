"""When the collector asks the oracle, and what (docs/reference-facts.md §5, dialog triggers).

* Attribute, at the first frame: about an attribute the instruction does not state and the
  target has a value for. The answer becomes a *known* attribute.
* Route, at a frame where the frontier nearest the target was chosen, once the move that
  followed proves real progress: more than ``route_progress`` metres walked and the geodesic
  distance to the target shorter than when the choice was made. The question is asked at the
  frame of the choice, with the state and view of that frame.
* Disambiguation, whenever an instance of the target's category that fits the known
  attributes is centred in the view (the oracle's own rule) within ``ask_range``; once per
  instance. In a house with several storeys, only about instances on the agent's storey
  (one seen down a stairwell is not "this one").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vlln.config import Positive, settings_dataclass
from vlln.datagen.collector.chooser import BEST, Choice
from vlln.datagen.collector.templates import (
    ATTRIBUTE_TEMPLATES,
    DISAMBIGUATION_TEMPLATES,
    ROUTE_TEMPLATES,
    fill,
)
from vlln.datagen.trajectory import Exchange
from vlln.oracle.disambiguation import centre_counts, is_centred, most_visible_of
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.storeys import Storeys
from vlln.tasks.oracle_protocol import Oracle, Question
from vlln.world.model import House, ObjectInstance

ATTRIBUTE, ROUTE, DISAMBIGUATION = "attribute", "route", "disambiguation"


@settings_dataclass
class DialogConfig:
    ask_range: Positive = 3.0  # m, floor-plan distance to a candidate's box
    route_progress: Positive = 1.0  # m walked after a best-frontier choice


@dataclass
class _PendingRoute:
    frame_index: int
    state: AgentState
    frame: Frame
    distance: float  # geodesic distance to the target at the choice
    walked: float = 0.0


class DialogTriggers:
    """Watches the walk frame by frame and asks the oracle when a trigger fires."""

    def __init__(
        self,
        oracle: Oracle,
        house: House,
        target: ObjectInstance,
        stated: frozenset[str],
        rng: np.random.Generator,
        config: DialogConfig | None = None,
        storeys: Storeys | None = None,
    ) -> None:
        self.oracle = oracle
        self.storeys = storeys
        self.house = house
        self.target = target
        self.stated = stated
        self.rng = rng
        self.config = config or DialogConfig()
        self.exchanges: list[Exchange] = []
        self.known: dict[str, str] = {}
        self._asked_about: set[int] = set()
        self._categories = {i.id: i.category for i in house.instances}
        wanted = [i.id for i in house.instances if i.category == target.category]
        self._of_category = np.zeros(max(wanted, default=0) + 2, bool)  # ids < 0 read slot 0
        self._of_category[wanted] = True
        self._pending: _PendingRoute | None = None
        self._choices_seen = 0
        self._last_position: tuple[float, float, float] | None = None

    # ----------------------------------------------------------------- triggers
    def at_start(self, state: AgentState, frame: Frame) -> None:
        """The attribute question (skipped when the instruction already states everything)."""
        values = {
            name: getattr(self.target.attributes, name)
            for name in ("color", "material", "texture", "shape", "size")
        }
        options = [name for name, value in values.items() if value and name not in self.stated]
        if "room" not in self.stated:
            options.append("room")
        if not options:
            return
        name = options[int(self.rng.integers(len(options)))]
        self._ask(0, ATTRIBUTE, ATTRIBUTE_TEMPLATES[name], state, frame)
        if name != "room":
            self.known[name] = values[name]

    def at_frame(
        self,
        frame_index: int,
        state: AgentState,
        frame: Frame,
        distance: float,
        choices: list[Choice],
        target_seen: bool,
    ) -> None:
        """Check the triggers on a new frame; ``choices`` is the chooser's log so far."""
        self._track_route(frame_index, state, frame, distance, choices, target_seen)
        self._check_disambiguation(frame_index, state, frame)

    def finish(self, distance: float) -> list[Exchange]:
        """Settle a pending route question at the end of the walk; the exchanges by frame."""
        self._settle_route(distance)
        return sorted(self.exchanges, key=lambda e: e.frame_index)

    # ----------------------------------------------------------------- route
    def _track_route(
        self,
        frame_index: int,
        state: AgentState,
        frame: Frame,
        distance: float,
        choices: list[Choice],
        target_seen: bool,
    ) -> None:
        pending = self._pending
        if pending is not None and self._last_position is not None:
            pending.walked += math.dist(self._last_position, state.position)
        self._last_position = state.position
        new = choices[self._choices_seen :]
        self._choices_seen = len(choices)
        if new or target_seen:
            self._settle_route(distance)
        if new and new[-1].rule == BEST and not target_seen:
            self._pending = _PendingRoute(frame_index, state, _copy(frame), distance)

    def _settle_route(self, distance: float) -> None:
        pending = self._pending
        self._pending = None
        if pending is None:
            return
        if pending.walked > self.config.route_progress and distance < pending.distance:
            self._ask(pending.frame_index, ROUTE, ROUTE_TEMPLATES, pending.state, pending.frame)

    # ----------------------------------------------------------------- disambiguation
    def _check_disambiguation(self, frame_index: int, state: AgentState, frame: Frame) -> None:
        ids = frame.instance_ids
        h, w = ids.shape
        centre = ids[h // 4 : 3 * h // 4, w // 4 : 3 * w // 4]
        if not np.take(self._of_category, centre, mode="clip").any():
            return  # the common case, checked without counting every id
        counts = centre_counts(ids)
        found = most_visible_of(counts, ids.shape, self._categories, self.target.category)
        if found is None:
            return
        candidate = self.house.instance(found)
        if candidate.id in self._asked_about or not self._fits_known(candidate):
            return
        if not is_centred(counts, candidate.id, ids):
            return
        x, y, z = state.position
        box = candidate.box
        if self.storeys is not None and (
            self.storeys.level_under(box.min[1]) != self.storeys.level_of(y)
        ):
            return
        gap = box.plan_distance(x, z)
        if gap > self.config.ask_range:
            return
        self._asked_about.add(candidate.id)
        self._ask(frame_index, DISAMBIGUATION, DISAMBIGUATION_TEMPLATES, state, frame)

    def _fits_known(self, instance: ObjectInstance) -> bool:
        return all(getattr(instance.attributes, k) == v for k, v in self.known.items())

    # ----------------------------------------------------------------- asking
    def _ask(
        self,
        frame_index: int,
        trigger: str,
        templates: tuple[str, ...],
        state: AgentState,
        frame: Frame,
    ) -> None:
        text = fill(templates, self.target.category, self.rng)
        reply = self.oracle.answer(Question(text, state, frame))
        self.exchanges.append(
            Exchange(frame_index, trigger, text, reply.answer, str(reply.question_type))
        )


def _copy(frame: Frame) -> Frame:
    return Frame(frame.rgb.copy(), frame.depth.copy(), frame.instance_ids.copy())
