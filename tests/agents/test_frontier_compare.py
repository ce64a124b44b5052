"""The comparing navigator (``frontier-compare``): with two chairs alike in view it asks the
helpful oracle which one is meant and walks to that one; the paper's oracle, which cannot say,
leaves it playing as the plain frontier agent."""

from __future__ import annotations

import math

import pytest

from tests.agents import world
from tests.sim import scenes
from vlln.agents.frontier import FrontierAgent
from vlln.agents.frontier.which_one import (
    COMPARISON_QUESTION,
    Pick,
    picked,
    read_clarification,
    read_comparison,
)
from vlln.agents.registry import make_agent
from vlln.oracle.settings import OracleBackend, OracleSettings
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.taxonomy import classify
from vlln.world.mesh import Mesh
from vlln.world.model import House, HouseGeometry, Room

NORTH_CHAIR = 3  # both chairs red, 1.4 m apart, in view together from the room's west end
SOUTH_CHAIR = 4


@pytest.fixture(scope="module")
def sim() -> Simulator:
    chairs = [
        world.chair(NORTH_CHAIR, "red", 5.0, 2.7, 0),
        world.chair(SOUTH_CHAIR, "red", 5.0, 1.3, 0),
    ]
    parts = [scenes.empty_room()]
    for chair in chairs:
        x, _, z = chair.box.center
        parts.append(scenes.box_object(chair.id, x, z, (0.5, 0.9, 0.5)))
    room = Room(0, "living room", ((0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (0.0, 4.0)))
    house = House("two_chairs", [room], [], chairs, geometry=HouseGeometry(Mesh.concatenate(parts)))
    return Simulator(house)


def _play(sim: Simulator, agent: str, oracle: OracleBackend, target: int) -> EpisodeRecord:
    episode = world.episode(sim, target, (1.0, 2.0), -math.pi / 2)
    config = TaskConfig(task=TaskType.IIGN, dialog_budget=5)
    env = NavigationEnv(
        [episode], config, world.OneScene(sim), OracleSettings(oracle).make(0), privileged=True
    )
    player = make_agent(agent, seed=3)
    world.play(env, player)
    assert isinstance(player, FrontierAgent)
    return env.record(agent, stop_reason=player.stop_reason())


@pytest.mark.parametrize("target", [NORTH_CHAIR, SOUTH_CHAIR])
def test_it_asks_which_one_and_walks_to_the_one_named(sim: Simulator, target: int) -> None:
    record = _play(sim, "frontier-compare", OracleBackend.HELPFUL, target)
    asked = [turn.question for turn in record.dialog]
    assert COMPARISON_QUESTION in asked
    comparison = record.dialog[asked.index(COMPARISON_QUESTION)]
    assert comparison.help_kind == "comparison"
    assert classify(record) == "success"
    assert record.stop_instance_id == target


def test_with_the_papers_oracle_it_plays_as_the_frontier_agent_after_asking(
    sim: Simulator,
) -> None:
    comparing = _play(sim, "frontier-compare", OracleBackend.RULES, SOUTH_CHAIR)
    plain = _play(sim, "frontier", OracleBackend.RULES, SOUTH_CHAIR)
    # The paper's oracle has no answer that names a place, so no candidate is picked or
    # ruled out by the comparison: the same chair is asked about and stopped at.
    assert COMPARISON_QUESTION in [turn.question for turn in comparing.dialog]
    assert comparing.stop_instance_id == plain.stop_instance_id


@pytest.mark.parametrize(
    ("answer", "place"),
    [
        ("It is the one on the right.", 1.0),
        ("Yes, it is the one on the left.", 0.0),
        ("It is the one in the middle.", 0.5),
        ("Only one chair is in your view, and it is the one I mean: it is in front of you.", 0.5),
        ("Neither: the chair I mean is not in your view. The one I mean is in the kitchen.", None),
        ("It is the one on the left (they are one behind the other).", 0.0),
    ],
)
def test_comparison_answers_name_a_place(answer: str, place: float | None) -> None:
    assert read_comparison(answer) == Pick(place)


@pytest.mark.parametrize(
    "answer",
    [
        "Turn left about 60 degrees.",
        "No.",
        "Sorry, I cannot answer your question now.",
        "It is the nearer one.",
        "It is red.",
    ],
)
def test_answers_without_a_place_pick_nothing(answer: str) -> None:
    assert read_comparison(answer) is None


def test_clarifications_name_a_place_or_none() -> None:
    left = "No. Two chairs are in view; the one I mean is the one on the left."
    assert read_clarification(left) == Pick(0.0)
    none = "No. Three chairs are in view, and none is the one I mean."
    assert read_clarification(none) == Pick(None)
    assert read_clarification("No, the one I mean is red.") is None
    assert read_clarification("Yes.") is None


def test_a_place_picks_from_the_candidates_left_to_right() -> None:
    columns = [(7, 0.2), (5, 0.45), (9, 0.8)]
    assert picked(Pick(0.0), columns) == 7
    assert picked(Pick(1.0), columns) == 9
    assert picked(Pick(0.5), columns) == 5
    assert picked(Pick(None), columns) is None
    assert picked(Pick(1.0), []) is None
