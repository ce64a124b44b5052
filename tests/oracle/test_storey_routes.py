"""Route answers in a two-storey house: on and near the stairs they say which way to go."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.follower import GreedyFollower
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator, SimulatorConfig
from vlln.sim.viewpoints import storey_view_points
from vlln.tasks.oracle_protocol import EpisodeContext, Question
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import ObjectInstance

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    camera = CameraSpec(width=160, height=120)
    with Simulator(generate_house(1, SMALL_TWO_STOREYS), SimulatorConfig(camera=camera)) as s:
        yield s


def _target_on(sim: Simulator, level: int) -> ObjectInstance:
    storeys = sim.storeys
    assert storeys is not None
    main = storeys.largest_component()
    labels = storeys.components()[0]
    for inst in sorted(sim.house.instances, key=lambda i: i.id):
        if inst.category == "stairs" or storeys.level_under(inst.box.min[1]) != level:
            continue
        points = storey_view_points(storeys, inst.box)
        if points and any(labels[storeys.node(*p)] == main for p in points):
            return inst
    raise AssertionError(f"no reachable target on storey {level}")


def _walk(sim: Simulator, start_level: int) -> tuple[RuleOracle, list[AgentState]]:
    """The oracle for a target on the other storey, and the expert's states on the way."""
    target = _target_on(sim, 1 - start_level)
    storeys = sim.storeys
    assert storeys is not None
    goals = tuple(storey_view_points(storeys, target.box))
    oracle = RuleOracle(0)
    oracle.start(EpisodeContext(sim, target, goals))
    follower = GreedyFollower(sim.nav, sim.distance_field(goals), 0.25, sim.config.motion)
    rng = np.random.default_rng(start_level)
    main = storeys.largest_component()
    start = storeys.sample_navigable_point(rng, main)
    while start[1] != storeys.floor_ys[start_level]:
        start = storeys.sample_navigable_point(rng, main)
    sim.reset(AgentState(start, 0.0))
    states = [sim.state]
    for _ in range(1000):
        action = follower.next_action(sim.state)
        if action == Action.STOP:
            break
        sim.move(action)
        states.append(sim.state)
    return oracle, states


def _ask(oracle: RuleOracle, sim: Simulator, state: AgentState, text: str) -> str:
    spec = sim.config.camera
    blank = Frame(
        np.zeros((spec.height, spec.width, 3), np.uint8),
        np.zeros((spec.height, spec.width), np.float32),
        np.zeros((spec.height, spec.width), np.int32),
    )
    return oracle.answer(Question(text, state, blank)).answer


@pytest.mark.parametrize(("start_level", "word"), [(0, "upstairs"), (1, "downstairs")])
def test_route_answers_on_and_near_the_stairs_say_which_way(
    sim: Simulator, start_level: int, word: str
) -> None:
    oracle, states = _walk(sim, start_level)
    floor = states[0].position[1]
    first_step = next(i for i, s in enumerate(states) if abs(s.position[1] - floor) > 0.05)
    last_step = max(
        i for i, s in enumerate(states) if min(abs(s.position[1]), abs(s.position[1] - 2.8)) > 0.01
    )
    # On the flight, and on the last half metre before it, the step answer names the way.
    near = [
        s
        for s in states[: first_step + 1]
        if np.hypot(
            s.position[0] - states[first_step].position[0],
            s.position[2] - states[first_step].position[2],
        )
        < 0.5
    ]
    on_flight = states[first_step : last_step - 3]
    assert len(on_flight) >= 5
    for state in [*near, *on_flight]:
        assert word in _ask(oracle, sim, state, "What should I do next?")
        answer = _ask(oracle, sim, state, "Can you give me directions to it?")
        assert f"go {word}" in answer.lower(), answer
    # Far from the stairs the answers are the usual ones.
    far = _ask(oracle, sim, states[0], "What should I do next?")
    assert "stairs" not in far
    assert "upstairs" not in far and "downstairs" not in far
    heading = _ask(oracle, sim, states[0], "Which way should I go?")
    assert heading.startswith(f"It is {word}, take the stairs."), heading
    # And past the stairs, on the other storey, they are about the target again.
    after = _ask(oracle, sim, states[-1], "What should I do next?")
    assert after.startswith("You are there")
