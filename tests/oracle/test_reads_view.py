"""`reads_view` names every question whose answer depends on the view, so a caller that
renders views only for those (the oracle service) gives the same answers as one that always
renders."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from oracle_training.question_sets import load_named_set
from vlln.oracle.rule_oracle import RuleOracle, reads_view
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.oracle_protocol import EpisodeContext, Question
from vlln.world.frame import yaw_of
from vlln.world.generator import HouseParameters, generate_house

SMALL = HouseParameters(min_rooms=4, max_rooms=5, min_area=60.0, max_area=90.0)
LOOKING = ("Is this the one?", "Can you see it from here?", "Is it in view?", "Do you see it?")


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    with Simulator(generate_house(31, SMALL)) as simulator:
        yield simulator


def blank(frame: Frame) -> Frame:
    """A view in which nothing at all is seen."""
    return Frame(frame.rgb, frame.depth, np.zeros_like(frame.instance_ids))


def test_questions_answered_without_the_view_get_the_same_answer_blind(sim: Simulator) -> None:
    grid = sim.grid
    component = grid.largest_component()
    target = next(  # a big piece of furniture, which the views from its view points show
        inst
        for inst in sim.house.instances
        if max(inst.box.size) >= 0.8
        and sum(grid.component_of(*p) == component for p in view_points(grid, inst.box)) >= 10
    )
    points = tuple(p for p in view_points(grid, target.box) if grid.component_of(*p) == component)
    sighted, blind = RuleOracle(seed=2), RuleOracle(seed=2)
    for oracle in (sighted, blind):
        oracle.start(EpisodeContext(sim, target, points))
    rng = np.random.default_rng(7)
    texts = [q.question for name in ("heldout", "train") for q in load_named_set(name)]
    asked = [*LOOKING, *(texts[int(i)] for i in rng.choice(len(texts), 300, replace=False))]
    states = [  # half facing the target from its view points, half anywhere
        AgentState((x, grid.floor_y, z), yaw_of(target.box.center[0] - x, target.box.center[2] - z))
        for x, z in points[:: max(1, len(points) // 10)][:10]
    ]
    for _ in range(10):
        x, z = grid.sample_navigable_point(rng, component)
        states.append(AgentState((x, grid.floor_y, z), float(rng.uniform(-3.14, 3.14))))
    seen_yes = 0
    for number, state in enumerate(states):
        frame = sim.render(state)
        for text in asked[number::7]:  # every question from a few poses
            seen = sighted.answer(Question(text, state, frame)).answer
            view = frame if reads_view(text) else blank(frame)
            assert blind.answer(Question(text, state, view)).answer == seen, text
            seen_yes += reads_view(text) and seen.startswith("Yes")
    assert seen_yes > 0  # blind, these would have been "No": the view decided them


def test_only_disambiguation_and_visibility_read_the_view() -> None:
    assert all(reads_view(text) for text in LOOKING)
    for text in ("What color is it?", "How far is it?", "Which room is it in?", "Am I close?"):
        assert not reads_view(text)
