"""The helpful oracle's recogniser: many phrasings, slips and cases of each kind of help, and
the paper's questions left to the rule oracle."""

from __future__ import annotations

import pytest

from tests.oracle.test_rule_oracle import QUESTIONS
from vlln.oracle.helpful.recognise import (
    CountScope,
    Dimension,
    FloorClaim,
    HelpKind,
    PathTopic,
    recognised,
)

PHRASINGS: dict[HelpKind, tuple[str, ...]] = {
    HelpKind.COMPARISON: (
        "is it the one on the left or the one on the right?",
        "Is it the left one or the right one?",
        "IS IT THE ONE ON TEH LFET",
        "the nearer one or the farther one?",
        "Which one is closer to me?",
        "is it the bigger one or the smaller one",
        "Is it the red one or the blue one?",
        "Which one is it?",
        "There are two plants here. Which one of these is the target?",
        "Is it the kitchen table or the dining table?",
        "front one or back one?",
        "I see two beds, which one?",
        "the one by the window or the one by the door?",
        "there are 2 toilets in front of me - left or right?",
        "I've got two candidates in view. Left or right?",
        "Would it be the toilet on the right-hand side?",
        "Can you help me choose between these two toilets?",
        "I'm seeing two curtains of different sizes. Which size is the one you mean?",
        "the sofa by my left hand or my right hand?",
        "pls tell me which tv: left or right",
        "Both lamps look alike, right or left?",
        "The lamp on the left or the lamp on the right?",
    ),
    HelpKind.CONFIRMATION: (
        "Are you sure?",
        "are u sure",
        "are you shure??",
        "Are you certain about that?",
        "really?",
        "How sure are you?",
        "Are you sure this is the one?",
        "Can you double-check? I don't want to pick the wrong lamp.",
        "Is that your final answer on which sofa?",
        "Positive?",
        "sure sure?",
        "no doubt about it?",
        "do you really mean this one",
        "you sure it's not the other cushion?",
        "Is there any chance it's a different mirror?",
        "is it safe to say I've found the shelf?",
        "Should I commit to this couch?",
        "Beyond any doubt?",
        "Absolutely certain?",
    ),
    HelpKind.DONE: (
        "so I'm done?",
        "Should I end the search here?",
        "is it ok to finish now?",
        "Should I keep searching or is this it?",
        "so no need to look any further?",
        "I'm going to stop here, is that ok?",
        "should i call it done?",
        "Do I need to keep going or have I got it?",
        "Is this where I should end the episode?",
        "Can we wrap up the search?",
        "Am I finished?",
        "Is that the end of the search?",
    ),
    HelpKind.PASSED: (
        "Did I pass it?",
        "did i pas it",
        "Have I walked past it?",
        "Did I overshoot the target?",
        "I think I missed it",
        "did I already see the toilet without noticing?",
        "Was the couch visible at some point earlier?",
        "Did I walk right by it?",
        "Was I in the right place earlier and then left?",
        "Have I already looked at the cabinet you mean?",
        "Could I have walked past it already?",
    ),
    HelpKind.CLOSER: (
        "Am I getting closer?",
        "am i gettign closer",
        "Am I getting warmer or colder?",
        "Am I closer than before?",
        "did I get any closer?",
        "Was I closer a minute ago?",
        "Am I on track?",
        "Did I take a wrong turn somewhere?",
        "have i been going the rigth way",
        "Am I heading in the right direction?",
        "Have I been moving away from the plant?",
        "Am I making any progress?",
        "hot or cold?",
    ),
    HelpKind.FLOOR: (
        "should I go upstairs?",
        "shoud i go upstars?",
        "Is it downstairs?",
        "Am I on the wrong floor?",
        "Which floor is it on?",
        "WHAT FLOOR IS IT ON",
        "Is it on this floor?",
        "How many floors does the house have?",
        "Is the house one storey or two?",
        "Is it on the floor I started on?",
        "should i go down",
        "Do I have to change floors?",
        "is it in the basement",
        "Do I need to go up or down?",
        "up or down?",
        "should i take these stairs",
        "Do I go up these stairs or down them?",
        "do i need the stairs for this one",
        "Is the sink above or below me?",
        "Is it on the main floor?",
    ),
    HelpKind.REROUTE: (
        "I think I'm lost, can you help?",
        "im lost",
        "Sorry, I am lost.",
        "Can you help me?",
        "I'm a bit confused, help me get there",
        "I am lost, I keep going in circles.",
    ),
    HelpKind.VISITED: (
        "have I been here before?",
        "Have I been in this room already?",
        "Have I looked in this room already?",
        "i feel like i've been here already, have i?",
        "have i checked this area yet",
        "Is this the first time I've been in this room?",
        "did i already go through this hallway",
        "I don't recognise this room. Have I been here?",
        "Am I in the same room I started in?",
        "Am I back where I started?",
        "Am I going in circles?",
        "Am I retracing my steps?",
        "I think I walked in a loop.",
        "Did I skip a room I should have checked?",
        "Was the towel in one of the rooms I just went through?",
        "Have I covered the part of the house where the curtain is?",
        "Have I been in the room it is in?",
        "how many rooms have I been through so far?",
        "Which rooms have I visited?",
        "Have I explored enough of this floor?",
        "Have I been in the kitchen yet?",
        "Am I in the wrong wing of the house?",
        "Am I in the right part of the house?",
        "Was I in here earlier?",
        "Did I already search the kitchen?",
        "Which rooms haven't I checked yet?",
    ),
    HelpKind.COUNT: (
        "How many chairs are there?",
        "hw many chairs r there",
        "how many of them are in the house?",
        "Is there more than one chair?",
        "How many lamps are in this house?",
        "count the lamps for me?",
        "Is this the only bed in the room?",
        "how many toilets does this place have",
        "How many tables are on this floor?",
        "What's the total count of desks?",
        "Can you give me a count of all the stools?",
        "How many beds does this room have?",
        "Count of mirrors here?",
        "is the shelf the only one of its kind here?",
        "How many sofas did I see on the way here?",
        "how many couches can be seen from this spot",
        "Are there two plants in here or just the one I can see?",
        "Is there more than one towel that I can see right now?",
    ),
    HelpKind.NEIGHBOURHOOD: (
        "What is around it?",
        "what else is near it?",
        "Describe its surroundings.",
        "Which things are around the plant?",
        "What's opposite the toilet?",
        "is there anything on top of it",
        "What is the sink near?",
        "What's in front of it?",
        "what's behind the bed?",
        "What's underneath it?",
        "What's on the wall near the couch?",
        "What is the counter sitting on?",
        "What is sitting on the table?",
        "What's hanging on the wall above it?",
    ),
    HelpKind.WINDOW: (
        "is it near a window?",
        "Is it by the window?",
        "is it neer a widnow?",
        "Is there a window close to it?",
        "is there a window behind it",
    ),
    HelpKind.OFF_TOPIC: (
        "How do I bake bread?",
        "how can I fix my bike",
        "How do you make pancakes?",
    ),
}


@pytest.mark.parametrize(
    ("kind", "text"), [(kind, text) for kind, texts in PHRASINGS.items() for text in texts]
)
def test_each_phrasing_is_recognised_as_its_kind(kind: HelpKind, text: str) -> None:
    request = recognised(text)
    assert request is not None and request.kind == kind, text


PAPERS = (
    *QUESTIONS,
    "Is this the one?",
    "Is this the right one?",
    "Am I close?",
    "Can I see it?",
    "What is next to it?",
    "Is it on the floor?",
    "Is it next to the floor lamp?",
    "How many steps?",
    "Is it a big one?",
    "Is it a red one?",
    "Should I turn left or right?",
    "Is it on the left?",
    "Where am I?",
    "Is it in the closet?",
    "How many drawers does the dresser have?",
    "How many questions can I ask?",
    "Sorry, I missed that.",
    "I am a bit lost. How far away is it?",
    "Should I stop here?",
    "Can I stop now?",
    "Left or right?",
    "Is it to my left or right?",
    "Should I take the door on my right?",
    "Now I go to the right or to the left?",
    "Am I facing the right way?",
    "Right turn now?",
    "What is it on?",
    "What is the chair next to?",
    "Is the counter near the stairs?",
    "Do I go left after the stairs?",
    "Is the toilet lid up or down?",
    "Am I in the basement?",
    "How do I get to the kitchen?",
    "How do i gte to the kichen",
    "How can I recognise the desk?",
    "Is it in the corridor between the two bedrooms?",
    "Should I go to the kitchen?",
    "Does the chair rock back and forth?",
    "Which rooms do I pass on the way?",
    "What time is it?",
    "Which quadrant is it in: front-left, front-right, back-left or back-right?",
)


@pytest.mark.parametrize("text", PAPERS)
def test_the_papers_questions_are_left_to_the_rule_oracle(text: str) -> None:
    assert recognised(text) is None


def test_what_a_question_names_is_read() -> None:
    sides = recognised("is it the one on the left or the one on the right?")
    assert sides is not None and sides.dimension == Dimension.SIDE
    assert sides.asked == ("left", "right") and not sides.yes_no
    near = recognised("Is it the nearer one?")
    assert near is not None and (near.dimension, near.asked, near.yes_no) == (
        Dimension.DISTANCE,
        ("near",),
        True,
    )
    colours = recognised("the light gray one or the gray one?")
    assert colours is not None and colours.dimension == Dimension.COLOR
    assert set(colours.asked) == {"light gray", "gray"}
    claims = {
        "should I go upstairs?": FloorClaim.UP,
        "do i go down the stairs": FloorClaim.DOWN,
        "Am I on the wrong floor?": FloorClaim.OTHER,
        "Is it on this floor?": FloorClaim.SAME,
        "Which floor is it on?": None,
    }
    for text, claim in claims.items():
        request = recognised(text)
        assert request is not None and request.floor_claim == claim, text


def test_a_remark_before_the_question_does_not_decide() -> None:
    floor = recognised("I am a bit lost. Should I go upstairs?")
    assert floor is not None and floor.kind == HelpKind.FLOOR
    assert recognised("I just walked past a sofa. What colour is the chair?") is None


def test_what_a_path_question_asks_is_read() -> None:
    topics = {
        "have I been here before?": (PathTopic.HERE, False),
        "Is this the first time I've been in this room?": (PathTopic.HERE, True),
        "Have I been in the kitchen yet?": (PathTopic.NAMED, False),
        "Am I in the same room I started in?": (PathTopic.START, False),
        "Am I going in circles?": (PathTopic.RETRACING, False),
        "Did I skip a room I should have checked?": (PathTopic.TARGET_ROOM, False),
        "how many rooms have I been through so far?": (PathTopic.ROOMS, False),
        "Am I in the wrong wing of the house?": (PathTopic.AREA, True),
        "Am I in the right part of the house?": (PathTopic.AREA, False),
    }
    for text, (topic, reverse) in topics.items():
        request = recognised(text)
        assert request is not None and (request.topic, request.reverse) == (topic, reverse), text
    named = recognised("Have I been in the hallway yet?")
    assert named is not None and named.rooms == ("corridor",)
    for text, reverse in {
        "Am I on track?": False,
        "Am I getting closer?": False,
        "Did I take a wrong turn somewhere?": True,
        "Was I closer a minute ago?": True,
        "Have I been moving away from the plant?": True,
    }.items():
        request = recognised(text)
        assert request is not None and (request.reverse, request.yes_no) == (reverse, True), text
    either = recognised("Am I getting warmer or colder?")
    assert either is not None and not either.yes_no


def test_what_a_count_counts_and_a_neighbourhood_question_relates_are_read() -> None:
    scopes = {
        "How many chairs are there?": {CountScope.HOUSE},
        "how many couches can be seen from this spot": {CountScope.HOUSE, CountScope.VIEW},
        "How many beds does this room have?": {CountScope.HOUSE, CountScope.ROOM},
        "How many sofas did I see on the way here?": {CountScope.HOUSE, CountScope.WALKED},
        "Are there two plants in here or just the one I can see?": {
            CountScope.HOUSE,
            CountScope.ROOM,
            CountScope.VIEW,
        },
    }
    for text, expected in scopes.items():
        request = recognised(text)
        assert request is not None and request.scopes == expected, text
    relations = {
        "is there anything on top of it": "above",
        "What's underneath it?": "under",
        "What is the counter sitting on?": "support",
        "What's in front of it?": "front",
        "what's behind the bed?": "behind",
        "What's on the wall near the couch?": "wall",
        "What is the sink near?": None,
    }
    for text, relation in relations.items():
        request = recognised(text)
        assert request is not None and request.relation == relation, text
    for text, claim in {
        "should i go down": FloorClaim.DOWN,
        "is it in the basement": FloorClaim.DOWN,
        "Do I have to change floors?": FloorClaim.OTHER,
        "up or down?": None,
        "Can I reach it without taking the stairs?": FloorClaim.SAME,
        "Does this house have more than one floor?": None,
        "Would going upstairs be a waste of time?": None,
        "Would I have to go downstairs for the couch?": FloorClaim.DOWN,
    }.items():
        request = recognised(text)
        assert request is not None and request.floor_claim == claim, text
    size = recognised("Two curtains here. Which size is the one you mean?")
    assert size is not None and size.dimension == Dimension.SIZE
    side = recognised("Would it be the toilet on the right-hand side?")
    assert side is not None and (side.dimension, side.asked, side.yes_no) == (
        Dimension.SIDE,
        ("right",),
        True,
    )


WIDER: tuple[tuple[str, HelpKind, PathTopic | None], ...] = (
    ("Was heading into the garage a mistake?", HelpKind.VISITED, PathTopic.ROUTE),
    ("I took the corridor. Was that a bad call?", HelpKind.VISITED, PathTopic.ROUTE),
    ("am I taking the long way round?", HelpKind.VISITED, PathTopic.ROUTE),
    ("did I turn back too early", HelpKind.VISITED, PathTopic.ROUTE),
    ("how far am I now compared to when I started?", HelpKind.VISITED, PathTopic.ROUTE),
    ("are we heading towards the sofa or away from it?", HelpKind.VISITED, PathTopic.ROUTE),
    ("which room did we skip?", HelpKind.VISITED, PathTopic.TARGET_ROOM),
    ("Did I miss the lamp in the bedroom back there?", HelpKind.VISITED, PathTopic.TARGET_ROOM),
    ("is the mirror in a room I already checked?", HelpKind.VISITED, PathTopic.TARGET_ROOM),
    ("we keep coming back to the same kitchen", HelpKind.VISITED, PathTopic.RETRACING),
    ("am I looking in totally the wrong area?", HelpKind.VISITED, PathTopic.AREA),
    ("have I entered this bathroom before?", HelpKind.VISITED, PathTopic.HERE),
    ("did we get within two metres of it?", HelpKind.PASSED, None),
    ("should we backtrack?", HelpKind.PASSED, None),
    ("top drawer unit or bottom drawer unit?", HelpKind.COMPARISON, None),
    ("left sink or right sink?", HelpKind.COMPARISON, None),
    ("left or right lamp", HelpKind.COMPARISON, None),
    ("is it the tall lamp or the lamp by the sofa?", HelpKind.COMPARISON, None),
    ("is the mirror you mean above the sink or below it?", HelpKind.COMPARISON, None),
    ("Is the plate on a table, a shelf or a counter?", HelpKind.NEIGHBOURHOOD, None),
    ("is the lamp standing by the sofa or the bed?", HelpKind.NEIGHBOURHOOD, None),
    ("what things are lying on the bed?", HelpKind.NEIGHBOURHOOD, None),
    ("what's on the dresser", HelpKind.NEIGHBOURHOOD, None),
    ("are there lamps on either side of the sofa?", HelpKind.NEIGHBOURHOOD, None),
    ("is it close to the doorway?", HelpKind.NEIGHBOURHOOD, None),
    ("Is it up here or should I go back down?", HelpKind.FLOOR, None),
    ("should we head up to look for the bed?", HelpKind.FLOOR, None),
    ("is it up in the attic?", HelpKind.FLOOR, None),
    ("is it on a diff level", HelpKind.FLOOR, None),
    ("Have we succeeded?", HelpKind.DONE, None),
    ("is the task over?", HelpKind.DONE, None),
    ("am I right that the vase by the tv is the one?", HelpKind.CONFIRMATION, None),
    ("is this it or did I pick the wrong one?", HelpKind.CONFIRMATION, None),
    ("how many chairs in my field of vision?", HelpKind.COUNT, None),
    ("is it one of several cushions?", HelpKind.COUNT, None),
    ("total lamps?", HelpKind.COUNT, None),
    ("will it rain tomorrow?", HelpKind.OFF_TOPIC, None),
    ("which crypto should I invest in", HelpKind.OFF_TOPIC, None),
    ("tell me a fun fact about dolphins", HelpKind.OFF_TOPIC, None),
)


@pytest.mark.parametrize(("text", "kind", "topic"), WIDER)
def test_wider_phrasings_are_recognised(text: str, kind: HelpKind, topic: PathTopic | None) -> None:
    request = recognised(text)
    assert request is not None and (request.kind, request.topic) == (kind, topic), text


@pytest.mark.parametrize(
    "text",
    (
        "Is the sofa blue or grey?",
        "Is it wooden or metal?",
        "Is it a chair or a sofa?",
        "left or right side?",
        "Left branch or right branch?",
        "Is it left or right of the bed?",
        "Should I go back the way I came?",
        "Is it only a couple of meters away?",
        "Is there a limit on the questions?",
        "Describe the path to the loft hatch.",
        "Sorry, my mistake.",
        "Is the weather lamp in the kitchen?",
    ),
)
def test_wider_patterns_leave_the_papers_alternatives_alone(text: str) -> None:
    assert recognised(text) is None, text
