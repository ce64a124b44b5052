"""The helpful oracle's answers from the house on a generated house: counts in view, in the
asker's room and along its walk, what is on, under, in front of and behind the target, the
floor to go to, a side asked of two candidates, and certainty without a certainty word."""

from __future__ import annotations

from collections import Counter

import pytest
from matplotlib.path import Path as PolygonPath

from tests.oracle.test_answers import _blank
from tests.oracle.test_helpful_oracle import _ask, _started, _upstairs, _visible, _walk_to
from tests.oracle.test_helpful_oracle import chair as chair  # the fixtures
from tests.oracle.test_helpful_oracle import views as views
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.knowledge import HouseIndex, object_phrase
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache
from vlln.world.model import ObjectInstance

_WORDS = dict(enumerate(["No", "One", "Two", "Three", "Four", "Five", "Six", "Seven", "Eight"]))


def _inside(sim: Simulator, room_id: int, x: float, z: float) -> bool:
    return bool(PolygonPath(sim.house.room(room_id).polygon).contains_point((x, z)))


def test_a_modal_can_is_never_the_counted_thing(
    sim: Simulator, chair: ObjectInstance, views: list[tuple[AgentState, Frame]]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    for state, frame in views:
        shown = len(_visible(sim, frame, "chair"))
        for text in (
            "how many chairs can be seen from this spot",
            "Is there more than one chair that I can see right now?",
            "How many chairs can I spot from this doorway?",
        ):
            answer = _ask(oracle, state, frame, text).answer
            assert answer.startswith(f"{_WORDS[shown]} chairs are in your view."), (text, answer)
            assert " can " not in answer
    state, frame = views[0]
    plants = _ask(oracle, state, frame, "Are there two plants in here or just the one I can see?")
    assert plants.answer.startswith(("No plant is in your view.", "One plant", "Two plants"))
    assert "plant" in plants.answer.split(".")[1]  # then those in the room


def test_counts_in_the_room_and_along_the_walk(sim: Simulator, chair: ObjectInstance) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    frame = _blank(sim)
    walked = _walk_to(sim, chair, 7)
    end = AgentState(walked[-1], 0.0)
    here = next(r for r in sim.house.rooms if _inside(sim, r.id, walked[-1][0], walked[-1][2]))
    in_room = sum(1 for inst in sim.house.instances_of("chair") if inst.room_id == here.id)
    answer = _ask(oracle, end, frame, "How many chairs does this room have?").answer
    assert answer.startswith(f"There are {_WORDS[in_room].lower()} chairs in this {here.type}.")
    assert "chairs in this house: " in answer
    total = len(sim.house.instances_of("chair"))
    for text in ("What's the total count of chairs?", "Can you give me a count of all the chairs?"):
        reply = _ask(oracle, end, frame, text)
        assert reply.help_kind == "count"
        assert reply.answer.startswith(f"There are {_WORDS[total].lower()} chairs in this house")
    rooms = {
        r.id
        for r in sim.house.rooms
        for x, _, z in walked
        if PolygonPath(r.polygon).contains_point((x, z))
    }
    passed = sum(1 for inst in sim.house.instances_of("chair") if inst.room_id in rooms)
    seen = _ask(oracle, end, frame, "How many chairs did I see on the way here?", tuple(walked))
    assert seen.answer.startswith(
        f"{_WORDS[passed]} chair{'s are' if passed > 1 else ' is'} in the rooms you have walked"
    ), seen.answer
    assert "The one I mean is one of those, in this " in seen.answer


@pytest.fixture(scope="module")
def couch(sim: Simulator) -> ObjectInstance:
    """A couch against a wall with things on it and a coffee table in front of it."""
    index = HouseIndex.build(sim.house)
    for inst in sim.house.instances_of("couch"):
        on_it = [r for r in index.relations_to.get(inst.id, []) if r.word == "on"]
        near = {sim.house.instance(r.object).category for r in index.relations.get(inst.id, [])}
        if on_it and "coffee table" in near and inst.attributes.placement == "against the wall":
            return inst
    raise AssertionError("the test house needs a couch with a coffee table in front of it")


def test_the_relation_asked_is_answered_from_the_relation_graph(
    sim: Simulator, couch: ObjectInstance
) -> None:
    index = HouseIndex.build(sim.house)
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, couch)
    state, frame = AgentState(_walk_to(sim, couch, 8)[0], 0.0), _blank(sim)

    def ask(text: str) -> str:
        reply = _ask(oracle, state, frame, text)
        assert (reply.help_kind, reply.question_type) == ("neighbourhood", "attribute"), text
        return reply.answer

    on_top = ask("is there anything on top of it")
    for relation in index.relations_to[couch.id]:
        if relation.word == "on":
            assert object_phrase(sim.house.instance(relation.subject)) in on_top.lower(), on_top
    assert "coffee table" in ask("What's in front of it?")
    assert "coffee table" not in ask("what's behind the couch?")
    assert ask("what's behind the couch?").startswith(
        "The wall is behind it: it stands against the wall."
    )
    assert ask("What is the couch sitting on?") == "It stands on the floor, against the wall."
    assert ask("What's underneath it?").startswith("Nothing is under it: it stands on the floor")
    # A thing on another: what it sits on is the paper's "on" relation, word for word.
    table = next(
        inst
        for inst in sim.house.instances_of("coffee table")
        if any(r.word == "on" for r in index.relations.get(inst.id, []))
    )
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, table)
    rules = _started(RuleOracle(0), sim, table)
    sitting = _ask(oracle, state, frame, "What is the coffee table sitting on?").answer
    assert sitting == _ask(rules, state, frame, "What is it on?").answer
    assert sitting.startswith("It is on the ")
    nothing = _ask(oracle, state, frame, "is there anything on top of it").answer
    on_table = [r for r in index.relations_to.get(table.id, []) if r.word == "on"]
    assert nothing.startswith("Nothing is on top of it.") == (not on_table)


def test_floor_phrasings_in_a_house_of_two_storeys(scenes: SceneCache) -> None:
    two, oracle, (below, _) = _upstairs(scenes)
    frame = _blank(two)
    answers = {
        "should i go down": "No. It is on the upper floor: go upstairs.",
        "Do I have to change floors?": "Yes. It is on the upper floor: go upstairs.",
        "up or down?": "It is on the upper floor: go upstairs.",
        "do i need the stairs for this one": "Yes. It is on the upper floor: go upstairs.",
        "is it in the basement": "No. It is on the upper floor: go upstairs.",
    }
    for text, expected in answers.items():
        reply = _ask(oracle, below, frame, text)
        assert (reply.answer, reply.help_kind) == (expected, "floor"), text


def test_left_or_right_of_two_in_view_and_certainty_without_its_word(
    sim: Simulator, chair: ObjectInstance, views: list[tuple[AgentState, Frame]]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, chair)
    checked = Counter[str]()
    for state, frame in views:
        shown = _visible(sim, frame, "chair")
        if len(shown) == 2 and chair.id in shown:
            other = next(i for i in shown if i != chair.id)
            if abs(shown[chair.id] - shown[other]) >= 0.05:
                side = "left" if shown[chair.id] < shown[other] else "right"
                for text in (
                    "there are 2 chairs in front of me - left or right?",
                    "I've got two candidates in view. Left or right?",
                ):
                    answer = _ask(oracle, state, frame, text).answer
                    assert answer == f"It is the one on the {side}.", (text, answer)
                asked = _ask(oracle, state, frame, "Would it be the chair on the right-hand side?")
                assert asked.answer.startswith("Yes" if side == "right" else "No"), asked.answer
                checked["side"] += 1
        if chair.id not in shown:
            for text in ("Is it safe to say I've found the chair?", "do you really mean this one"):
                answer = _ask(oracle, state, frame, text).answer
                assert answer.startswith("I am sure: "), (text, answer)
                assert "not the one I mean" in answer or "none of the chairs" in answer
            assert _ask(oracle, state, frame, "Positive?").answer.startswith("Yes, I am sure: ")
            checked["sure"] += 1
    assert checked["side"] >= 1 and checked["sure"] >= 1
