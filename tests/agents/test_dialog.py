import math

import pytest

from vlln.agents.frontier import dialog
from vlln.oracle.classify import analyse_question
from vlln.oracle.topics import RouteKind
from vlln.tasks.oracle_protocol import QuestionType
from vlln.tasks.spec import REFUSAL_MESSAGE
from vlln.world.catalogue.registry import default_catalogue
from vlln.world.model import Attributes


@pytest.fixture
def vocabulary() -> dialog.Vocabulary:
    known = [
        Attributes(color="dark brown", material="wood", shape="desk", size="small"),
        Attributes(color="brown", material="plain", shape="round", size="medium"),
    ]
    return dialog.Vocabulary.from_attributes(known)


def test_longest_colour_wins_and_adjectives_name_materials(vocabulary: dialog.Vocabulary) -> None:
    assert vocabulary.parse("It is dark brown.") == {"color": "dark brown"}
    assert vocabulary.parse("a brown wooden thing") == {"color": "brown", "material": "wood"}
    assert vocabulary.parse("The painted medium-sized one") == {
        "material": "plain",
        "size": "medium",
    }
    assert vocabulary.parse("Sorry, I cannot answer your question now.") == {}


def test_every_known_colour_is_understood(vocabulary: dialog.Vocabulary) -> None:
    assert vocabulary.parse("It is light blue.") == {"color": "light blue"}
    assert vocabulary.parse("It is navy.") == {"color": "navy"}


def test_target_phrase_stops_before_rooms_and_relations() -> None:
    text = "Find the small red chair in the kitchen next to the white table."
    assert dialog.target_phrase(text) == "small red chair"
    assert dialog.target_phrase("In the bedroom, locate the blue lamp.") == "blue lamp"
    assert dialog.target_phrase("Walk to the chair that is near the bed.") == "chair"


def test_stated_attributes_ignore_the_noun_and_other_objects(
    vocabulary: dialog.Vocabulary,
) -> None:
    # "desk" is a shape value too; as the category noun it says nothing about the target.
    assert dialog.stated_attributes("Search for the desk.", "desk", vocabulary) == {}
    text = "Go to the small round desk next to the dark brown chair."
    assert dialog.stated_attributes(text, "desk", vocabulary) == {
        "size": "small",
        "shape": "round",
    }
    # A finer name replacing the category noun is dropped as well.
    assert dialog.stated_attributes("Find the brown armchair.", "chair", vocabulary) == {
        "color": "brown"
    }


def test_yes_no_and_refusals() -> None:
    assert dialog.parse_yes_no("Yes, that is it.") is True
    assert dialog.parse_yes_no("No, the one I mean is red.") is False
    assert dialog.parse_yes_no("I cannot tell.") is None
    assert dialog.is_refusal(REFUSAL_MESSAGE)
    assert not dialog.is_refusal("No.")


@pytest.mark.parametrize(
    ("answer", "degrees"),
    [
        ("Turn left about 60 degrees.", 60.0),
        ("Turn right about 120 degrees, then go forward.", -120.0),
        ("Turn left.", 30.0),
        ("Go forward.", 0.0),
        ("It is straight ahead.", 0.0),
        ("Turn around.", 180.0),
        ("1. go forward 2 m, turn right at the sofa", 0.0),
        ("The chair is behind you; turn around.", 180.0),
        ("It is right next to you. Turn left about 40 degrees.", 40.0),
    ],
)
def test_route_answers_give_a_signed_turn(answer: str, degrees: float) -> None:
    turn = dialog.parse_route(answer)
    assert turn is not None
    assert math.degrees(turn) == pytest.approx(degrees)


def test_route_answers_without_a_direction_give_nothing() -> None:
    assert dialog.parse_route("Sorry, I cannot answer your question now.") is None
    assert dialog.parse_route("You are there.") is None
    assert dialog.says_arrived("You are there.")
    assert dialog.says_arrived("It is right next to you. It is straight ahead.")
    assert not dialog.says_arrived("Turn left about 60 degrees.")


def test_a_no_that_means_come_closer_is_told_apart() -> None:
    answer = "No, not from here: you are still about 4 meters from it."
    assert dialog.parse_yes_no(answer) is False
    assert dialog.says_too_far(answer)
    assert not dialog.says_too_far("No, the one I mean is red.")


def test_known_attributes_filter_candidates() -> None:
    red = Attributes(color="red", material="wood")
    assert dialog.matches_known(red, {})
    assert dialog.matches_known(red, {"color": "red"})
    assert not dialog.matches_known(red, {"color": "red", "material": "metal"})


AGENT_QUESTIONS = [
    *((t, QuestionType.ATTRIBUTE, None) for ts in dialog.ATTRIBUTE_TEMPLATES.values() for t in ts),
    *((t, QuestionType.DISAMBIGUATION, None) for t in dialog.DISAMBIGUATION_TEMPLATES),
    *((t, QuestionType.ROUTE, RouteKind.ORIENTATION) for t in dialog.ROUTE_TEMPLATES),
]


@pytest.mark.parametrize(("template", "question_type", "route_kind"), AGENT_QUESTIONS)
def test_the_oracle_reads_each_agent_question_alike_for_every_category(
    template: str, question_type: QuestionType, route_kind: RouteKind | None
) -> None:
    # Which object the agent looks for must not change the kind of answer it gets.
    read = {
        (a.question_type, a.route_kind)
        for a in (analyse_question(template.format(category=c.name)) for c in default_catalogue())
    }
    assert read == {(question_type, route_kind)}
