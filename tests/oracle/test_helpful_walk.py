"""The helpful oracle's answers about the walk so far, on a generated house: the rooms walked
through (read here with matplotlib's polygon test, apart from the oracle's), the trend along
the path, whether the search is done, and the refusal of questions about nothing in the
house."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from matplotlib.path import Path as PolygonPath

from tests.oracle.test_answers import _blank
from tests.oracle.test_helpful_oracle import Point, _ask, _back, _started, _walk_to
from vlln.oracle.helpful.oracle import HelpfulOracle
from vlln.oracle.knowledge import room_name
from vlln.oracle.rule_oracle import TYPE_REFUSAL, RuleOracle
from vlln.sim.agent import AgentState
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.world.frame import yaw_of
from vlln.world.model import ObjectInstance, Room


def _room_of(sim: Simulator, point: Point) -> Room | None:
    return next(
        (r for r in sim.house.rooms if PolygonPath(r.polygon).contains_point(point[::2])), None
    )


def _rooms_along(sim: Simulator, walked: list[Point]) -> list[Room]:
    """The rooms of the walk in order, each stretch once."""
    rooms: list[Room] = []
    for point in walked:
        room = _room_of(sim, point)
        if room is not None and (not rooms or rooms[-1].id != room.id):
            rooms.append(room)
    return rooms


def _asker(
    sim: Simulator, bed: ObjectInstance, kind: str, question_type: str | None = None
) -> Callable[[str, list[Point]], str]:
    """Ask the helpful oracle, started on ``bed``, at the end of a walked path: the answer,
    checked to be help of ``kind`` (and ``question_type``)."""
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, bed)
    frame = _blank(sim)

    def ask(text: str, path: list[Point]) -> str:
        reply = _ask(oracle, AgentState(path[-1], 0.0), frame, text, tuple(path))
        assert reply.help_kind == kind, text
        assert question_type in (None, reply.question_type), text
        return reply.answer

    return ask


@pytest.fixture(scope="module")
def bed(sim: Simulator) -> ObjectInstance:
    """The first bed by id: a target in a room of its own type among several."""
    return min(sim.house.instances_of("bed"), key=lambda inst: inst.id)


@pytest.fixture(scope="module")
def walk(sim: Simulator, bed: ObjectInstance) -> list[Point]:
    """A shortest-path walk through three rooms or more, each once, ending in the bed's."""
    for seed in range(40):
        walked = _walk_to(sim, bed, seed)
        rooms = _rooms_along(sim, walked)
        if (
            len(rooms) >= 3
            and len({room.id for room in rooms}) == len(rooms)
            and rooms[-1].id == bed.room_id
        ):
            return walked
    raise AssertionError("no walk to the bed goes through three rooms into its own")


def test_rooms_visited_come_from_the_walked_path(
    sim: Simulator, bed: ObjectInstance, walk: list[Point]
) -> None:
    rooms = _rooms_along(sim, walk)
    first, last = rooms[0], rooms[-1]
    assert last.id == bed.room_id
    ask = _asker(sim, bed, "visited", "other")

    start = walk[:2]
    assert ask("have I been here before?", start).startswith(
        f"You started in this {room_name(first)} and have not left it yet."
    )
    assert ask("Did I skip a room I should have checked?", start).startswith(
        "No, you have not been in its room yet"
    )
    assert ask("have I been here before?", walk).startswith(
        f"No, this is the first time you are in this {room_name(last)}."
    )
    assert ask("Is this the first time I've been in this room?", walk).startswith("Yes, ")
    assert ask("Am I in the same room I started in?", walk).startswith(
        f"No, you started in the {room_name(first)}; now you are in the {room_name(last)}."
    )
    count = ask("how many rooms have I been through so far?", walk)
    assert count.startswith(f"You have been in {len(rooms)} of this house's "), count
    assert f"{len(sim.house.rooms)} rooms so far" in count
    assert ask(f"Have I been in the {room_name(first)} yet?", walk).startswith("Yes, you were")
    unseen = next(r for r in sim.house.rooms if r.type not in {room.type for room in rooms})
    assert ask(f"Have I been in the {room_name(unseen)}?", walk).startswith("No, you have not")
    # Back along the walk into the room before the bed's: been there, and in the bed's room.
    before = rooms[-2]
    last_in_before = max(i for i, p in enumerate(walk) if _room_of(sim, p) == before)
    back = [*walk, *walk[last_in_before:-1][::-1]]
    assert ask("Have I already been in this room?", back).startswith(
        f"Yes, you were in this {room_name(before)} before, "
    )
    assert ask("Am I going in circles?", back).startswith("Yes, ")
    assert ask("Did I skip a room I should have checked?", back).startswith(
        "Yes, you were in its room, the "
    )


def test_on_track_and_wrong_turn_follow_the_trend_along_the_path(
    sim: Simulator, bed: ObjectInstance, walk: list[Point]
) -> None:
    ask = _asker(sim, bed, "closer")

    on_the_way = walk[: 2 * len(walk) // 3]
    assert ask("Am I on track?", on_the_way).startswith("Yes, you are getting closer")
    assert ask("Did I take a wrong turn somewhere?", on_the_way).startswith(
        "No, you are getting closer"
    )
    gone_by = _back(walk, 3.0)
    assert ask("Was I closer a minute ago?", gone_by).startswith("Yes, you are getting farther")
    wrong = ask("have i been going the rigth way", gone_by)
    assert wrong.startswith("No, you are getting farther") and "To get closer, " in wrong
    assert ask("Am I getting warmer or colder?", gone_by).startswith("You are getting farther")


def test_seen_it_earlier_says_whether_the_walk_passed_it_or_its_room(
    sim: Simulator, bed: ObjectInstance, walk: list[Point]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, bed)
    frame = _blank(sim)
    first_room = _rooms_along(sim, walk)[0]
    start = [p for p in walk if _room_of(sim, p) is not None][:3]
    assert _room_of(sim, start[-1]) == first_room
    reply = _ask(
        oracle,
        AgentState(start[-1], 0.0),
        frame,
        "did I see the bed without noticing?",
        tuple(start),
    )
    assert reply.help_kind == "passed"
    assert reply.answer.startswith("No, you have not passed it, and you have not been in its room")
    gone_by = _back(walk, 3.0)
    passed = _ask(
        oracle, AgentState(gone_by[-1], 0.0), frame, "Did I walk right by it?", tuple(gone_by)
    )
    assert passed.answer.startswith("Yes, you passed the bed")


def test_done_is_where_the_follower_would_stop(sim: Simulator, bed: ObjectInstance) -> None:
    rules = _started(RuleOracle(0), sim, bed)
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, bed)
    cx, _, cz = bed.box.center
    x, z = view_points(sim.grid, bed.box)[0]
    there = AgentState((x, 0.0, z), yaw_of(cx - x, cz - z))
    frame = sim.render(there)
    for text in ("so I'm done?", "Should I end the search here?", "is it ok to finish now?"):
        reply = _ask(oracle, there, frame, text)
        assert reply.answer.startswith("You are there: you can stop here."), text
        assert (reply.help_kind, reply.question_type) == ("done", "route")
    far = AgentState(_walk_to(sim, bed, 3)[0], 0.0)
    away = _ask(oracle, far, _blank(sim), "Should I keep searching or is this it?").answer
    assert away.startswith("You are not there yet: the bed I mean is about ")
    assert "To get closer, " in away
    for text in ("Should I stop here?", "Can I stop now?"):  # the paper's step questions
        reply = _ask(oracle, far, _blank(sim), text)
        assert (
            reply.help_kind == "schema"
            and reply.answer == _ask(rules, far, _blank(sim), text).answer
        )


def test_questions_about_nothing_in_the_house_get_the_papers_refusal(
    sim: Simulator, bed: ObjectInstance
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, bed)
    state, frame = AgentState(_walk_to(sim, bed, 3)[0], 0.0), _blank(sim)
    baked = _ask(oracle, state, frame, "How do I bake bread?")
    assert (baked.answer, baked.help_kind) == (TYPE_REFUSAL, "off_topic")
    rules = _ask(_started(RuleOracle(0), sim, bed), state, frame, "How do I bake bread?")
    assert rules.answer != TYPE_REFUSAL  # the rule oracle reads it as a way asked
    timed = _ask(oracle, state, frame, "What time is it?")
    assert (timed.answer, timed.help_kind) == (TYPE_REFUSAL, "schema")
    way = _ask(oracle, state, frame, "How do I get to the bed?")
    assert way.help_kind == "schema" and way.answer != TYPE_REFUSAL


def test_a_verdict_on_the_walk_judges_its_last_stretch_and_its_start(
    sim: Simulator, bed: ObjectInstance, walk: list[Point]
) -> None:
    ask = _asker(sim, bed, "visited")

    on_the_way = walk[: 2 * len(walk) // 3]
    for text in ("I turned left back there. Was that the wrong call?", "did I turn back too soon?"):
        answer = ask(text, on_the_way)
        assert answer.startswith("No. Your last few meters took you closer"), answer
        assert "Since the start you are about " in answer and " closer: it was " in answer
    assert "about the shortest way" in ask("did I detour a lot?", on_the_way)
    gone_by = _back(walk, 3.0)
    wrong = ask("Was turning around a mistake?", gone_by)
    assert wrong.startswith("Yes. Your last few meters took you farther"), wrong
    assert "To get closer, " in wrong
    assert ask("how much closer am I than at the start?", walk).startswith(
        "Your last few meters took you closer"
    )
    room = room_name(_rooms_along(sim, walk)[-1])
    assert ask(f"was going into the {room} a mistake?", walk).startswith(
        f"No. The bed is in the {room}."
    )


def test_wider_phrasings_reach_their_answers_on_a_real_house(
    sim: Simulator, bed: ObjectInstance, walk: list[Point]
) -> None:
    oracle = _started(HelpfulOracle(RuleOracle(0)), sim, bed)
    state, frame = AgentState(walk[-1], 0.0), _blank(sim)
    for text in ("What's the square root of 144?", "how many calories in a banana"):
        assert _ask(oracle, state, frame, text).answer == TYPE_REFUSAL, text  # never a count
    rooted = _ask(oracle, state, frame, "What's the square root of 144?")
    assert rooted.help_kind == "off_topic"  # the rule oracle answers it as an attribute
    support = _ask(oracle, state, frame, "Is the bed on a rug, a mat, or the floor?")
    assert support.help_kind == "neighbourhood"
    assert support.answer.startswith(("It is on ", "It stands on the floor"))
    counted = _ask(oracle, state, frame, "total beds in the house?")
    assert counted.help_kind == "count" and "bed" in counted.answer
    passed = _ask(oracle, state, frame, "have I already been within a couple of metres of it?")
    assert passed.help_kind == "passed"
