"""Question classification: accuracy of the shipped model on the question sets, topics,
values named in questions, typos."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from oracle_training.question_sets import TRAINING_SETS, load_named_set
from oracle_training.training import training_sets, with_typo
from vlln.oracle.classifier.model import packaged_classifier, prepared
from vlln.oracle.classify import (
    AttributeTopic,
    OtherTopic,
    RouteKind,
    StepChoice,
    analyse_question,
    classify_question,
)
from vlln.oracle.question_set import LabelledQuestion, accuracy_of, evaluate_classifier
from vlln.tasks.oracle_protocol import QuestionType

A = QuestionType.ATTRIBUTE
R = QuestionType.ROUTE
D = QuestionType.DISAMBIGUATION
X = QuestionType.OTHER
STEP = RouteKind.STEP
TRAIN = load_named_set("train")
HELDOUT = load_named_set("heldout")
# Training leaves out any question of another set that reads the same as a held-out one. The
# held-out set (v23 and v24, two writers) was written without sight of the classifier; the
# shipped model types 98.1 % of it (docs/oracle-classifier.md). The floor guards regressions.
HELDOUT_FLOOR = 0.975
TRAINED = training_sets()


def _misclassified(questions: list[LabelledQuestion]) -> list[tuple[str, str, str]]:
    return [
        (q.question, classify_question(q.question).value, q.question_type.value)
        for q in questions
        if classify_question(q.question) != q.question_type
    ]


def test_the_training_set_is_large_and_covers_every_type() -> None:
    assert len(TRAIN) >= 500
    for question_type in QuestionType:
        assert sum(q.question_type == question_type for q in TRAIN) >= 20


def test_the_heldout_set_is_many_questions_of_every_type_none_in_other_sets() -> None:
    assert len(HELDOUT) >= 150
    for question_type in QuestionType:
        assert sum(q.question_type == question_type for q in HELDOUT) >= 20
    trained = {prepared(q.question) for questions in TRAINED.values() for q in questions}
    assert not [q.question for q in HELDOUT if prepared(q.question) in trained]


@pytest.mark.slow
@pytest.mark.parametrize("name", TRAINING_SETS)
def test_accuracy_on_each_training_set(name: str) -> None:
    questions = TRAINED[name]
    accuracy = accuracy_of(evaluate_classifier(questions))
    assert accuracy >= 0.98, f"{name}: {accuracy:.3f}; misclassified: {_misclassified(questions)}"


def test_accuracy_on_the_heldout_set() -> None:
    accuracy = accuracy_of(evaluate_classifier(HELDOUT))
    assert accuracy >= HELDOUT_FLOOR, f"held-out accuracy {accuracy:.3f}: {_misclassified(HELDOUT)}"


def test_route_granularity_on_the_heldout_set() -> None:
    # Of the route questions typed as route (a wrong type is the accuracy test's miss), the
    # share given the wrong kind: orientation, path or step. v23 and v24: 7 of 442.
    analysed = [(q, analyse_question(q.question)) for q in HELDOUT if q.question_type == R]
    routes = [(q, a) for q, a in analysed if a.question_type == R]
    wrong = [
        (q.question, a.route_kind, q.route_kind) for q, a in routes if a.route_kind != q.route_kind
    ]
    assert len(routes) >= 0.9 * len(analysed)
    assert len(wrong) <= 0.05 * len(routes), wrong


def _ending(question: str) -> str:
    return "?!" if "?" in question else "!."


def _doubled_spaces(question: str) -> str:
    return question.replace(" ", "  ")


@pytest.mark.slow
@pytest.mark.parametrize(
    "transform",
    [str.upper, str.lower, lambda q: f"  {q.rstrip('?.!')}{_ending(q)}  ", _doubled_spaces],
)
def test_case_punctuation_and_spacing_do_not_change_the_type(
    transform: Callable[[str], str],
) -> None:
    # Only whether a question mark is there is read ("Got it?" asks, "Got it." acknowledges).
    for item in TRAIN[::7]:
        question = item.question
        changed = transform(question)
        assert classify_question(changed) == classify_question(question), (question, changed)


# Plain questions of every type, each typed with slips by a seeded generator below.
_PLAIN = [
    ("what color is the chair", A),
    ("what material is the table made of", A),
    ("which room is the bookshelf in", A),
    ("what is next to the sofa", A),
    ("how big is the wardrobe", A),
    ("which way should i go to find the lamp", R),
    ("how do i get to the kitchen from here", R),
    ("should i turn left at the corridor", R),
    ("is the bathroom behind me", R),
    ("is this the television you mean", D),
    ("am i looking at the right cabinet", D),
    ("is the pillow in front of me the target", D),
    ("what room am i standing in", X),
    ("how far away is the refrigerator", X),
    ("am i getting closer to the target", X),
    ("what time is it right now", X),
]


def test_questions_typed_with_slips_keep_their_type() -> None:
    rng = np.random.default_rng(7)
    right = total = 0
    for question, question_type in _PLAIN:
        assert classify_question(question) == question_type, question
        for _ in range(5):
            typed = with_typo(with_typo(question, rng), rng)
            right += classify_question(typed) == question_type
            total += 1
    assert right >= 0.9 * total, f"{right} of {total}"


@pytest.mark.parametrize(
    ("typed", "room", "color"),
    [
        ("is it in the bathrom", "bathroom", None),
        ("is the chiar in the kichen", "kitchen", None),
        ("is it yelow", None, "yellow"),
        ("is the lamp purpel", None, "purple"),
    ],
)
def test_typed_values_are_still_found(typed: str, room: str | None, color: str | None) -> None:
    analysis = analyse_question(typed)
    assert analysis.rooms == ((room,) if room else ())
    assert analysis.colors == ((color,) if color else ())


@pytest.mark.parametrize(
    ("question", "topic"),
    [
        ("What color is it?", AttributeTopic.COLOR),
        ("Is it wooden?", AttributeTopic.MATERIAL),
        ("What does it feel like, smooth?", AttributeTopic.TEXTURE),
        ("What shape is the table?", AttributeTopic.SHAPE),
        ("How big is it?", AttributeTopic.SIZE),
        ("Which room is it in?", AttributeTopic.ROOM),
        ("Where is the chair?", AttributeTopic.LOCATION),
        ("What is next to it?", AttributeTopic.NEARBY),
        ("What is it sitting on?", AttributeTopic.SUPPORT),
        ("What kind of lamp is it?", AttributeTopic.CATEGORY),
        ("Can you describe the target?", AttributeTopic.DESCRIPTION),
    ],
)
def test_attribute_topics(question: str, topic: AttributeTopic) -> None:
    analysis = analyse_question(question)
    assert analysis.question_type == A
    assert analysis.attribute == topic


@pytest.mark.parametrize(
    ("question", "topic"),
    [
        ("What room am I in?", OtherTopic.AGENT_ROOM),
        ("How far is it?", OtherTopic.DISTANCE),
        ("Am I close?", OtherTopic.PROGRESS),
        ("Can I see it from here?", OtherTopic.VISIBILITY),
        ("What time is it?", OtherTopic.UNKNOWN),
    ],
)
def test_other_topics(question: str, topic: OtherTopic) -> None:
    analysis = analyse_question(question)
    assert analysis.question_type == X
    assert analysis.other == topic


@pytest.mark.parametrize(
    ("question", "choice"),
    [
        ("Should I turn left?", StepChoice.LEFT),
        ("Do I turn right here?", StepChoice.RIGHT),
        ("Should I keep going straight?", StepChoice.FORWARD),
        ("Should I stop here?", StepChoice.STOP),
        ("Should I turn left or right?", None),
        ("What should I do next?", None),
    ],
)
def test_step_questions_report_the_action_they_propose(
    question: str, choice: StepChoice | None
) -> None:
    analysis = analyse_question(question)
    assert analysis.route_kind == STEP
    assert analysis.step_choice == choice


def test_values_named_in_a_question_are_extracted() -> None:
    analysis = analyse_question("Is it light gray, and is it made of wood in the kitchen?")
    assert analysis.yes_no
    assert analysis.colors == ("light gray",)  # not also "gray"
    assert analysis.materials == ("wood",)
    assert analysis.rooms == ("kitchen",)
    assert analyse_question("Is it in this room?").this_room
    assert not analyse_question("What color is it?").yes_no
    assert analyse_question("I'm at the fridge. Isn't it red?").yes_no  # the last sentence
    island = analyse_question("Is the kitchen island white?")
    assert island.rooms == ()  # the "kitchen" of a kitchen island is no room
    assert island.text == "is the kitchen island white"


def test_empty_and_meaningless_input_is_other() -> None:
    for text in ["", "   ", "?!"]:
        analysis = analyse_question(text)
        assert analysis.question_type == X and analysis.other == OtherTopic.UNKNOWN


def test_the_classifier_is_loaded_once() -> None:
    assert packaged_classifier() is packaged_classifier()
