"""Question classification: accuracy on the packaged labelled sets, topics, values, typos."""

from __future__ import annotations

from collections.abc import Callable

import pytest

from vlln.oracle.classify import (
    AttributeTopic,
    OtherTopic,
    RouteKind,
    StepChoice,
    analyse_question,
    classify_question,
)
from vlln.oracle.normalisation import normalise, rephrase
from vlln.oracle.protocol import QuestionType
from vlln.oracle.question_set import (
    LabelledQuestion,
    accuracy_of,
    evaluate_classifier,
    load_packaged_question_set,
)

A = QuestionType.ATTRIBUTE
R = QuestionType.ROUTE
X = QuestionType.OTHER
STEP = RouteKind.STEP
TRAIN = load_packaged_question_set("train")
# The held-out set (v4) is written separately and never tuned against; the questions in it
# that also occur in the training set are left out of its measurement. First measurement of
# v4: 92.7 % (202 of 218 unseen questions; 93.3 % of all 240); the benchmark's target is 95 %.
# The floor guards regressions.
HELDOUT_FLOOR = 0.90


def unseen_heldout() -> list[LabelledQuestion]:
    seen = {normalise(q.question) for q in TRAIN}
    return [q for q in load_packaged_question_set("heldout") if normalise(q.question) not in seen]


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


def test_the_unseen_heldout_questions_are_many_and_cover_every_type() -> None:
    heldout = unseen_heldout()
    assert len(heldout) >= 150
    for question_type in QuestionType:
        assert sum(q.question_type == question_type for q in heldout) >= 20


def test_accuracy_on_the_training_set() -> None:
    accuracy = accuracy_of(evaluate_classifier(TRAIN))
    assert accuracy >= 0.98, f"accuracy {accuracy:.3f}; misclassified: {_misclassified(TRAIN)}"


def test_accuracy_on_the_heldout_set() -> None:
    accuracy = accuracy_of(evaluate_classifier(unseen_heldout()))
    assert accuracy >= HELDOUT_FLOOR, f"held-out accuracy {accuracy:.3f}"


def test_route_granularity_on_the_training_set() -> None:
    routes = [q for q in TRAIN if q.question_type == R]
    assert all(q.route_kind is not None for q in routes)
    wrong = [(q.question, analyse_question(q.question).route_kind, q.route_kind) for q in routes]
    wrong = [w for w in wrong if w[1] != w[2]]
    assert len(wrong) <= 0.03 * len(routes), wrong


@pytest.mark.parametrize(
    "transform",
    [str.upper, str.lower, lambda q: f"  {q.rstrip('?.!')}?!  ", lambda q: q.replace(" ", "  ")],
)
def test_case_punctuation_and_spacing_do_not_change_the_type(
    transform: Callable[[str], str],
) -> None:
    for item in TRAIN:
        question = item.question
        changed = transform(question)
        assert classify_question(changed) == classify_question(question), (question, changed)


@pytest.mark.parametrize(
    ("typed", "meant"),
    [
        ("wat colr is it", "what color is it"),
        ("wich way shud i go", "which way should i go"),
        ("should i trun rigth", "should i turn right"),
        ("What's the materail?", "what is the material"),
        ("is ths the one", "is this the one"),
        ("where's the bathrom", "where is the bathroom"),
        ("how do i get thru the hallway", "how do i get through the hallway"),
        ("is taht the chiar", "is that the chair"),
        ("how do i gte to the kichen", "how do i get to the kitchen"),
        ("teh lfet side", "the left side"),
    ],
)
def test_normalise_fixes_typos_contractions_and_chat_spellings(typed: str, meant: str) -> None:
    assert normalise(typed) == meant


@pytest.mark.parametrize(
    "text",
    [
        "is that the book",
        "let me see that lamp",
        "weather",
        "show me over there",
        "head to my current position",
        "what time is it",
    ],
)
def test_normalise_leaves_known_words_alone(text: str) -> None:
    assert normalise(text) == text


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


def test_empty_and_meaningless_input_is_other() -> None:
    for text in ["", "   ", "?!", "asdf qwer", "12345"]:
        assert classify_question(text) == X


@pytest.mark.parametrize(
    ("question", "question_type"),
    [
        # Politeness wrappers and embedded questions keep the inner question's type.
        ("Could you tell me whether this is the target?", QuestionType.DISAMBIGUATION),
        ("I would like to know what color it is.", A),
        ("Please verify if the lamp I am facing is the goal.", QuestionType.DISAMBIGUATION),
        ("Do you know where I should go?", R),
        # Subject before auxiliary, as non-native speakers often write it.
        ("Where I should go now?", R),
        ("In which room I am?", X),
        # Declarative word order and bare demonstratives.
        ("This lamp is the correct one?", QuestionType.DISAMBIGUATION),
        ("that?", QuestionType.DISAMBIGUATION),
        # A wh-question about "this" is not a disambiguation question.
        ("What room is this?", X),
    ],
)
def test_wording_variants_keep_their_type(question: str, question_type: QuestionType) -> None:
    assert classify_question(question) == question_type


def test_the_agent_as_a_reference_point_marks_a_candidate_not_a_neighbour() -> None:
    assert classify_question("Is the chair next to me the target?") == QuestionType.DISAMBIGUATION
    analysis = analyse_question("What is next to the chair?")
    assert analysis.attribute == AttributeTopic.NEARBY


@pytest.mark.parametrize(
    ("typed", "meant"),
    [
        ("could you tell me whether this is the target", "is this the target"),
        ("please confirm whether the red chair is the goal", "confirm is the red chair the goal"),
        ("how i can go to the kitchen", "how can i go to the kitchen"),
        ("is this the chair you want", "is this the target chair"),
    ],
)
def test_rephrase_restores_the_question_frame(typed: str, meant: str) -> None:
    assert rephrase(typed) == meant
