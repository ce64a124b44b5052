"""Answers about the candidates in view: which one it is, how sure the oracle is, whether the
search is done, and the clarification added to "is this the one?" when several candidates
are in view.

The oracle knows which instance the target is; what it cannot know is which candidate the
asker means by "this". So it is certain when the view holds one candidate (or none that is
the target), and says it cannot tell when it holds several, naming the target among them.
"""

from __future__ import annotations

import math

from vlln.oracle.answers import distance_words, room_phrase, with_article
from vlln.oracle.disambiguation import DISAMBIGUATION_RANGE
from vlln.oracle.helpful import patterns as p
from vlln.oracle.helpful.path import advice, direction
from vlln.oracle.helpful.recognise import Dimension, HelpRequest
from vlln.oracle.helpful.view import (
    Candidate,
    candidates_in_view,
    counted,
    end_word,
    place,
    place_in_view,
    place_phrase,
    plural,
    target_among,
    which_one,
)
from vlln.oracle.knowledge import EpisodeKnowledge
from vlln.oracle.route import CANNOT_ANSWER
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame


def answer_comparison(
    knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState, frame: Frame
) -> str:
    """Which of the candidates in view is the target, by the property the question names."""
    candidates = candidates_in_view(knowledge, state, frame)
    target = target_among(knowledge, candidates)
    category = knowledge.target.category
    if target is None:
        where = _where(knowledge, state)
        if not candidates:  # "coffee table or side table?": its kind tells them apart
            kind = with_article(knowledge.target.fine_category or category)
            where = where.replace("The one I mean is in", f"The one I mean is {kind}, in")
            return f"I can't tell from here: no {category} is in your view. {where}".rstrip()
        none = "Neither" if len(candidates) == 2 else "None of them"
        return f"{none}: the {category} I mean is not in your view. {where}".rstrip()
    if len(candidates) == 1:
        return (
            f"Only one {category} is in your view, and it is the one I mean: it is "
            f"{place_in_view(target)}."
        )
    value, phrase = _told_apart(request, candidates, target)
    if request.yes_no and len(request.asked) == 1:
        agrees = request.asked[0] == value
        return f"{'Yes' if agrees else 'No'}, it is {phrase}."
    return f"It is {phrase}."


_VALUES = {Dimension.SIDE: "column", Dimension.DISTANCE: "distance", Dimension.SIZE: "log_volume"}
_ALIKE = {
    "column": "they are one behind the other",
    "distance": "they are about as far from you",
    "log_volume": "they are about the same size",
}


def _told_apart(
    request: HelpRequest, candidates: list[Candidate], target: Candidate
) -> tuple[str, str]:
    """The target's value by the asked property ("left", "near", "big", a colour; "" when it
    has none there), and the words that name it; where that property does not tell the
    candidates apart, the words that do, and why."""
    fallback = which_one(candidates, target)
    dimension = request.dimension
    if dimension is not None and dimension in _VALUES:
        value = _VALUES[dimension]
        at = place(candidates, target, value)
        if at is None:
            return "", f"{fallback} ({_ALIKE[value]})"
        return end_word(at, len(candidates), value), place_phrase(at, len(candidates), value)
    if dimension == Dimension.COLOR:
        color = target.instance.attributes.color
        if not color:
            return "", f"{fallback} (I do not know its colour)"
        shared = any(c.instance.attributes.color == color for c in candidates if c is not target)
        phrase = f"the {color} one" + (f", {fallback}" if shared else "")
        if len(request.asked) > 1 and color not in request.asked:
            return color, f"neither: {phrase}"
        return color, phrase
    return "", fallback


def answer_confirmation(
    knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState, frame: Frame
) -> str:
    """ "Are you sure?", "should I commit to this couch?": certain when the view holds one
    candidate or none is the target. Only a question of certainty alone ("are you sure?",
    "positive?") is answered "yes, I am sure", since a yes to "is there any chance it is a
    different mirror?" would say the opposite."""
    candidates = candidates_in_view(knowledge, state, frame)
    target = target_among(knowledge, candidates)
    category = knowledge.target.category
    sure = "Yes, I am sure" if p.CERTAINTY_ALONE.search(request.text) else "I am sure"
    if not candidates:
        where = _where(knowledge, state)
        return f"I can't tell from here: no {category} is in your view. {where}".rstrip()
    if target is None:
        seen = f"the {category}" if len(candidates) == 1 else f"none of the {plural(category)}"
        verb = "is not" if len(candidates) == 1 else "is"
        where = _where(knowledge, state)
        return f"{sure}: {seen} in your view {verb} the one I mean. {where}".rstrip()
    if len(candidates) == 1:
        far = ""
        if target.distance > DISAMBIGUATION_RANGE:
            far = f", about {round(target.distance)} meters away"
        return f"{sure}: it is the one {place_in_view(target)}{far}."
    return (
        f"I can't tell which one you mean from here: {counted(len(candidates), category)} are "
        f"in view. The one I mean is {which_one(candidates, target)}."
    )


def answer_done(knowledge: EpisodeKnowledge, state: AgentState, frame: Frame) -> str:
    """ "So I am done?", "should I end the search here?": done where the follower would stop
    (within the success radius of a view point of the target); else how far it is, whether it
    is in view and the next step. Said without yes or no, which "do I need to keep going?"
    would turn around."""
    x, y, z = state.position
    distance = knowledge.geodesic(x, z, y)
    if distance == math.inf:
        return CANNOT_ANSWER
    category = knowledge.target.category
    candidates = candidates_in_view(knowledge, state, frame)
    target = target_among(knowledge, candidates)
    seen = ""
    if target is not None:
        alone = f"the one {place_in_view(target)}"
        seen = f" It is in your view: {which_one(candidates, target) if candidates[1:] else alone}."
    if distance < knowledge.follower.goal_radius:
        return f"You are there: you can stop here.{seen}"
    where = f"{distance_words(distance)} away, {direction(knowledge, state)}"
    return (
        f"You are not there yet: the {category} I mean is {where}.{seen} {advice(knowledge, state)}"
    ).rstrip()


def clarification(knowledge: EpisodeKnowledge, state: AgentState, frame: Frame) -> str | None:
    """Which candidate the target is, when "is this the one?" is asked with several in view
    (None with fewer): "Two chairs are in view; the one I mean is the one on the left."."""
    candidates = candidates_in_view(knowledge, state, frame)
    if len(candidates) < 2:
        return None
    target = target_among(knowledge, candidates)
    seen = counted(len(candidates), knowledge.target.category)
    seen = seen[0].upper() + seen[1:]
    if target is None:
        none = "neither" if len(candidates) == 2 else "none"
        return f"{seen} are in view, and {none} is the one I mean."
    return f"{seen} are in view; the one I mean is {which_one(candidates, target)}."


def _where(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    room = knowledge.target_room
    if room is None:
        return ""
    return f"The one I mean is in {room_phrase(knowledge, room, state)}."
