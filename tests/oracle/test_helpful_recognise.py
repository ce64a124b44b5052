"""The helpful oracle's recogniser: many phrasings, slips and cases of each kind of help, and
the paper's questions left to the rule oracle."""

from __future__ import annotations

import pytest

from tests.oracle.test_rule_oracle import QUESTIONS
from vlln.oracle.helpful.recognise import Dimension, FloorClaim, HelpKind, recognised

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
    ),
    HelpKind.PASSED: (
        "Did I pass it?",
        "did i pas it",
        "Have I walked past it?",
        "Did I overshoot the target?",
        "I think I missed it",
    ),
    HelpKind.CLOSER: (
        "Am I getting closer?",
        "am i gettign closer",
        "Am I getting warmer or colder?",
        "Am I closer than before?",
        "did I get any closer?",
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
    ),
    HelpKind.REROUTE: (
        "I think I'm lost, can you help?",
        "im lost",
        "Sorry, I am lost.",
        "Can you help me?",
        "I'm a bit confused, help me get there",
        "Have I been in this room already?",
        "I think I walked in a loop.",
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
    ),
    HelpKind.NEIGHBOURHOOD: (
        "What is around it?",
        "what else is near it?",
        "Describe its surroundings.",
        "Which things are around the plant?",
        "What's opposite the toilet?",
    ),
    HelpKind.WINDOW: (
        "is it near a window?",
        "Is it by the window?",
        "is it neer a widnow?",
        "Is there a window close to it?",
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
