"""Question classification on a hand-labelled set with typos, paraphrases and chat spellings."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from vlln.oracle.classify import (
    AttributeTopic,
    OtherTopic,
    RouteKind,
    StepChoice,
    analyse_question,
    classify_question,
)
from vlln.oracle.normalisation import normalise
from vlln.oracle.protocol import QuestionType

A = QuestionType.ATTRIBUTE
R = QuestionType.ROUTE
D = QuestionType.DISAMBIGUATION
X = QuestionType.OTHER
ORIENT, PATH, STEP = RouteKind.ORIENTATION, RouteKind.PATH, RouteKind.STEP

# (question, type) or (question, ROUTE, granularity).
LABELLED: list[tuple[Any, ...]] = [
    # Attribute
    ("What color is it?", A),
    ("what colour is the chair", A),
    ("Wat colr is it?", A),
    ("Which color does the target have?", A),
    ("Is it red?", A),
    ("is the sofa blue or grey?", A),
    ("What is it made of?", A),
    ("what material is the table", A),
    ("Is it wooden?", A),
    ("is it made out of metal", A),
    ("What's the materail of the chair?", A),
    ("What does it look like?", A),
    ("Can you describe it?", A),
    ("describe the target plz", A),
    ("Tell me more about the bed.", A),
    ("Any distinctive features?", A),
    ("How big is it?", A),
    ("how large is the cabinet?", A),
    ("Is it small or large?", A),
    ("what size is the rug", A),
    ("How tall is the lamp?", A),
    ("Which room is it in?", A),
    ("In which room can I find the plant?", A),
    ("Is it in the kitchen?", A),
    ("is the chair in the living room", A),
    ("Is it in this room?", A),
    ("whcih room is the target in", A),
    ("What room is the tv in?", A),
    ("Where is it?", A),
    ("where's the chair?", A),
    ("Where can I find the towel?", A),
    ("Where is the target located?", A),
    ("What is near it?", A),
    ("What is it next to?", A),
    ("what's next to the chair", A),
    ("What objects are around it?", A),
    ("Is it beside the bed?", A),
    ("What is it on?", A),
    ("What is the cup sitting on?", A),
    ("Is it on the floor?", A),
    ("Is it against the wall?", A),
    ("is it on a table", A),
    ("What kind of chair is it?", A),
    ("What type of lamp should I look for?", A),
    ("What shape is it?", A),
    ("Is it round?", A),
    ("What is the texture of the rug?", A),
    ("Is it smooth?", A),
    ("What am I looking for?", A),
    ("Which chair do you mean?", A),
    ("Can you give me some hints about the target?", A),
    ("What is it?", A),
    ("Any other details?", A),
    ("how wide is it", A),
    ("Could you tell me the colour of the sofa?", A),
    ("Is the bed white?", A),
    ("Does it have a dark brown color?", A),
    ("What's it made from?", A),
    ("is the target made of glass?", A),
    ("What does the target look like?", A),
    ("Give me a description of the object", A),
    ("How big is the target object?", A),
    ("Is it a large one?", A),
    ("In what room is it located?", A),
    ("Is the lamp in the bedroom?", A),
    ("Which part of the house is it in?", A),
    ("Where exactly is the picture?", A),
    ("What is beside the target?", A),
    ("What furniture is close to it?", A),
    ("Is there anything on top of it?", A),
    ("Is it under the window?", A),
    ("What is the fine-grained category?", A),
    ("What sort of plant is it?", A),
    ("Is it rectangular?", A),
    ("What pattern does it have?", A),
    ("Tell me about the target.", A),
    ("what shoud I look for?", A),
    ("What are its features?", A),
    ("Is the chair leather?", A),
    ("hw big is it", A),
    ("WHAT COLOR IS THE TARGET???", A),
    ("color?", A),
    ("material?", A),
    ("hey what colour r the cushions", A),
    ("what color is the thing im looking for", A),
    ("is it black or white?", A),
    ("Made of what?", A),
    ("what's the target's material", A),
    ("Is the desk metallic?", A),
    ("Could you describe the chair in more detail?", A),
    ("what does it look liek", A),
    ("is it big?", A),
    ("How high is the shelf?", A),
    ("what room is the bed in?", A),
    ("is it in the bathrom?", A),
    ("where is the towl", A),
    ("what's around the target?", A),
    ("is it next to a sofa?", A),
    ("what is the lamp standing on?", A),
    ("is the vase on the table?", A),
    ("what kind of bed?", A),
    ("any more clues?", A),
    ("what does the goal object look like?", A),
    ("which one is the target?", A),
    ("Can you tell me what colour the target is?", A),
    ("Is the armchair green?", A),
    ("what's the colur of it", A),
    ("Does it feel soft?", A),
    ("Is it made from plastic?", A),
    ("Is it a big or a small cabinet?", A),
    ("Tell me something about how it looks.", A),
    ("Is it placed in the dining room?", A),
    ("In which room is the target?", A),
    ("Where is the goal?", A),
    ("Is there a table near it?", A),
    ("What is the object above it?", A),
    ("What's under it?", A),
    ("What is the target's shape?", A),
    ("Which chair is it?", A),
    ("Anything special about it?", A),
    ("is it in the same room as me?", A),
    # Route
    ("Which way should I go?", R, ORIENT),
    ("Which way is it?", R, ORIENT),
    ("Which direction is it in?", R, ORIENT),
    ("Where should I go?", R, PATH),
    ("How do I get there?", R, PATH),
    ("What should I do next?", R, STEP),
    ("Should I turn left?", R, STEP),
    ("Which direction is the target?", R, ORIENT),
    ("which drection should I head", R, ORIENT),
    ("How can I reach the sofa?", R, PATH),
    ("how do i get to the bed from here", R, PATH),
    ("Where should I go now?", R, PATH),
    ("Should I turn left or right here?", R, STEP),
    ("left or right?", R, STEP),
    ("Shoud I go straight?", R, STEP),
    ("Should I keep going forward?", R, STEP),
    ("Do I turn right here?", R, STEP),
    ("What's my next move?", R, STEP),
    ("What now?", R, STEP),
    ("next step?", R, STEP),
    ("Can you guide me to it?", R, PATH),
    ("Show me the way to the chair.", R, PATH),
    ("Give me directions to the target.", R, PATH),
    ("What route should I take?", R, PATH),
    ("which way is the kitchen?", R, ORIENT),
    ("Is it on my left or my right?", R, ORIENT),
    ("Is the target to my left?", R, ORIENT),
    ("Which side is it on?", R, ORIENT),
    ("Where is it from here?", R, ORIENT),
    ("Point me to the target.", R, ORIENT),
    ("Is it behind me?", R, ORIENT),
    ("Is it ahead of me?", R, ORIENT),
    ("which door should I take?", R, PATH),
    ("Which room should I go to?", R, PATH),
    ("How to get to the target?", R, PATH),
    ("Where do I go next?", R, PATH),
    ("Should I go upstairs or downstairs?", R, STEP),
    ("Should I stop here?", R, STEP),
    ("Should I turn around?", R, STEP),
    ("wich way shud i go", R, ORIENT),
    ("Should i trun rigth", R, STEP),
    ("where to go now?", R, PATH),
    ("Lead me to the lamp please", R, PATH),
    ("Which way do I turn?", R, ORIENT),
    ("What direction should I face?", R, ORIENT),
    ("Do I go left here?", R, STEP),
    ("Which way now?", R, ORIENT),
    ("how do I find the bed", R, PATH),
    ("Keep going straight?", R, STEP),
    ("Should I continue down this hallway?", R, STEP),
    ("what is the best way there?", R, PATH),
    ("Where should I search?", R, PATH),
    ("Which way to the target?", R, ORIENT),
    ("Which way?", R, ORIENT),
    ("How do I go there?", R, PATH),
    ("Can you tell me how to get to the chair?", R, PATH),
    ("Where do I need to go?", R, PATH),
    ("Should I go through the door?", R, STEP),
    ("Turn left or go straight?", R, STEP),
    ("What is the next action?", R, STEP),
    ("Should I move forward?", R, STEP),
    ("Which direction should I go in?", R, ORIENT),
    ("Help me get to the target.", R, PATH),
    ("Do I need to turn around?", R, STEP),
    ("Take me there.", R, PATH),
    ("In which direction is the sofa?", R, ORIENT),
    ("Should I go right at the end of the corridor?", R, STEP),
    ("how to reach it", R, PATH),
    ("What's the quickest route?", R, PATH),
    ("Should I head towards the kitchen?", R, STEP),
    ("which room shoud I search in?", R, PATH),
    ("which way do i go from here", R, ORIENT),
    ("how do i get to it", R, PATH),
    ("wher should i go next", R, PATH),
    ("left?", R, STEP),
    ("right or straight?", R, STEP),
    ("should i go back?", R, STEP),
    ("should i turn rihgt here", R, STEP),
    ("what should I do now?", R, STEP),
    ("which direction now?", R, ORIENT),
    ("can you show me the route?", R, PATH),
    ("how can i get there from here?", R, PATH),
    ("do i keep going straight", R, STEP),
    ("is it to the right?", R, ORIENT),
    ("should I leave this room?", R, STEP),
    ("How do I reach the target from my position?", R, PATH),
    ("Where should I head next?", R, PATH),
    ("Should I go left at the door?", R, STEP),
    ("Which way do I need to go?", R, ORIENT),
    ("Go forward?", R, STEP),
    ("Should I follow this corridor?", R, STEP),
    ("Is it straight ahead?", R, ORIENT),
    ("Do I turn back?", R, STEP),
    ("Please guide me.", R, PATH),
    ("How do I get out of this room?", R, PATH),
    ("What direction is the goal in?", R, ORIENT),
    ("Could you give me directions?", R, PATH),
    # Disambiguation
    ("Is this the one?", D),
    ("Is it this chair?", D),
    ("Is the chair in front of me the right one?", D),
    ("Is this it?", D),
    ("is that the target?", D),
    ("Is this the chair you mean?", D),
    ("Is this the right chair?", D),
    ("Is that the correct one?", D),
    ("Have I found it?", D),
    ("Did I find the target?", D),
    ("Is this the sofa you are looking for?", D),
    ("this one?", D),
    ("Is it the one in front of me?", D),
    ("is ths the one", D),
    ("Is the one I see the target?", D),
    ("Am I looking at the target?", D),
    ("Is the lamp I am looking at the one?", D),
    ("Is this red chair the target?", D),
    ("Are these the ones?", D),
    ("Is that it over there?", D),
    ("I found a chair, is it the one?", D),
    ("Is this what you meant?", D),
    ("Is this bed the target bed?", D),
    ("that one?", D),
    ("Is the table right here the goal?", D),
    ("Is this the correct object?", D),
    ("is it that one on the left?", D),
    ("Is this the right one?", D),
    ("Is this the chair?", D),
    ("Is the sofa in front of me the target?", D),
    ("Is this it?!", D),
    ("Is that the lamp you want?", D),
    ("Found it?", D),
    ("Is this the target object?", D),
    ("Is that one the right one?", D),
    ("Is it the chair I'm looking at?", D),
    ("Is the bed right here the one?", D),
    ("this the one?", D),
    ("Is THIS the right table", D),
    ("is it this one?", D),
    ("is the chair infront of me the target?", D),
    ("Is this the one you're talking about?", D),
    ("Is that chair the target?", D),
    ("is this the right bed?", D),
    ("did i find it?", D),
    ("is this correct?", D),
    ("is it the one in front of me right now", D),
    ("Is this chair the one?", D),
    ("Is the lamp in front of me the target?", D),
    ("Is it that sofa?", D),
    ("So is this the right plant?", D),
    ("Is this object the target?", D),
    ("Am I looking at the right one?", D),
    ("Is the one on the left the target?", D),
    # Other
    ("What room am I in?", X),
    ("Where am I?", X),
    ("Which room is this?", X),
    ("Am I in the kitchen?", X),
    ("Is this the bathroom?", X),
    ("How far is it?", X),
    ("how far away is the target", X),
    ("What is the distance to the chair?", X),
    ("How many steps to the target?", X),
    ("Is it far?", X),
    ("Is it close?", X),
    ("Am I close?", X),
    ("Am I getting closer?", X),
    ("Am I near the target?", X),
    ("Am I on the right track?", X),
    ("Am I almost there?", X),
    ("Am I going the right way?", X),
    ("Can I see it from here?", X),
    ("Is the target visible now?", X),
    ("Is it in view?", X),
    ("Hello!", X),
    ("Thank you.", X),
    ("What time is it?", X),
    ("Who are you?", X),
    ("Can you help?", X),
    ("What is the weather like?", X),
    ("How many chairs are there?", X),
    ("ok", X),
    ("How long until I get there?", X),
    ("Am I far from it?", X),
    ("How are you today?", X),
    ("What's your name?", X),
    ("How far do I still have to go?", X),
    ("Am I nearly there?", X),
    ("Is the target nearby?", X),
    ("What room is this?", X),
    ("Which room am I in right now?", X),
    ("Am I getting warmer?", X),
    ("Can you see the target?", X),
    ("Nice house, isn't it?", X),
    ("Why?", X),
    ("Thanks a lot!", X),
    ("How much further?", X),
    ("What floor am I on?", X),
    ("how far am I from the target?", X),
    ("is it far from here?", X),
    ("am i close to it?", X),
    ("where am i right now", X),
    ("what room is this?", X),
    ("can you see it?", X),
    ("how many meters left?", X),
    ("who made this house?", X),
    ("good job", X),
    ("How close am I?", X),
    ("Is it still far?", X),
    ("Am I heading in the right direction?", X),
    ("What room am I currently in?", X),
    ("Is the target in view?", X),
    ("What is your favourite colour?", X),
    ("How long have I been walking?", X),
    ("Is this the kitchen?", X),
    ("Where am I now?", X),
]


def test_the_labelled_set_is_large_and_covers_every_type() -> None:
    assert len(LABELLED) >= 120
    for question_type in QuestionType:
        assert sum(1 for item in LABELLED if item[1] == question_type) >= 40


def test_classification_accuracy_on_the_labelled_set() -> None:
    wrong = [(item[0], classify_question(item[0]), item[1]) for item in LABELLED]
    wrong = [w for w in wrong if w[1] != w[2]]
    accuracy = 1.0 - len(wrong) / len(LABELLED)
    assert accuracy >= 0.95, f"accuracy {accuracy:.3f}; misclassified: {wrong}"


def test_route_granularity_on_the_labelled_set() -> None:
    routes = [item for item in LABELLED if len(item) == 3]
    assert len(routes) == sum(1 for item in LABELLED if item[1] == R)
    wrong = [(q, analyse_question(q).route_kind, k) for q, _, k in routes]
    wrong = [w for w in wrong if w[1] != w[2]]
    assert len(wrong) <= 0.05 * len(routes), wrong


@pytest.mark.parametrize(
    "transform",
    [str.upper, str.lower, lambda q: f"  {q.rstrip('?.!')}?!  ", lambda q: q.replace(" ", "  ")],
)
def test_case_punctuation_and_spacing_do_not_change_the_type(
    transform: Callable[[str], str],
) -> None:
    for item in LABELLED:
        question = item[0]
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
    ],
)
def test_normalise_fixes_typos_contractions_and_chat_spellings(typed: str, meant: str) -> None:
    assert normalise(typed) == meant


@pytest.mark.parametrize("text", ["is that the book", "let me see that lamp", "weather"])
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
