"""Answers about the asker's progress: whether it passed the target, whether it is getting
closer (measured along the path it walked), which storey the target is on, and the way
from where it stands when it is lost.

Distances are walking distances to the target's view points, as the rule oracle's; the path
is :attr:`vlln.tasks.oracle_protocol.Question.path`, the positions walked so far.
"""

from __future__ import annotations

import math

from vlln.oracle.answers import distance_words, room_phrase
from vlln.oracle.helpful.path import (
    Path,
    advice,
    ago,
    direction,
    target_room_visit,
    walked_back,
    walking,
)
from vlln.oracle.helpful.recognise import FloorClaim, HelpRequest
from vlln.oracle.knowledge import EpisodeKnowledge, room_name
from vlln.oracle.route import CANNOT_ANSWER, answer_path
from vlln.sim.agent import AgentState

PASSED_NEAR = 1.0  # m of walking distance: the asker came this close to the target ...
PASSED_MARGIN = 1.0  # m: ... and is now this much farther than it was there
TREND_WALK = 2.0  # m walked back along the path to the position "a few steps ago"
TREND_CHANGE = 0.5  # m of walking distance that count as closer or farther


def answer_passed(knowledge: EpisodeKnowledge, state: AgentState, path: Path) -> str:
    """ "Did I pass it?", "did I see it without noticing?": yes when the path came within
    :data:`PASSED_NEAR` of it and the asker has since walked :data:`PASSED_MARGIN` farther
    away; otherwise no, and whether the walk has been in the target's room."""
    now = walking(knowledge, state.position)
    if now == math.inf:
        return CANNOT_ANSWER
    if now < knowledge.follower.goal_radius:
        return "No, you are there: it is right here."
    category = knowledge.target.category
    where = f"it is {distance_words(now)} away, {direction(knowledge, state)}"
    nearest = min((walking(knowledge, p) for p in path[:-1]), default=math.inf)
    if nearest <= PASSED_NEAR and now >= nearest + PASSED_MARGIN:
        return f"Yes, you passed the {category}: you walked right by it. Now {where}."
    room = knowledge.target_room
    if room is None:
        return f"No, you have not passed it: {where}."
    now_in, left = target_room_visit(knowledge, state, path)
    there = f"the {room_name(room)}"  # where it lies is said by the direction
    if now_in:
        return f"No, you have not passed it: {where}, in this {room_name(room)}."
    if left is not None:
        return (
            f"No, you have not passed it, though you were in its room, {there}, {ago(left)}: "
            f"{where}."
        )
    return (
        f"No, you have not passed it, and you have not been in its room yet: {where}, in {there}."
    )


def answer_closer(
    knowledge: EpisodeKnowledge,
    state: AgentState,
    path: Path,
    *,
    yes_no: bool = True,
    reverse: bool = False,
) -> str:
    """ "Am I getting closer?", "did I take a wrong turn?": the walking distance now against
    that of the position :data:`TREND_WALK` metres back along the path, with the next step
    unless the asker is getting closer. With ``yes_no``, yes or no answer what the question
    proposed: getting closer, or (``reverse``) farther."""
    now = walking(knowledge, state.position)
    if now == math.inf:
        return CANNOT_ANSWER
    away = distance_words(now)
    earlier = walked_back(path, TREND_WALK)
    step = advice(knowledge, state)
    if earlier is None:
        return f"You have not moved yet; it is {away} away. {step}".rstrip()
    change = walking(knowledge, earlier) - now
    if abs(change) < TREND_CHANGE:  # "not really" would say no to "did I go the wrong way?"
        same = "Not really" if yes_no and not reverse else "About as far as before"
        return f"{same}: it is still {away} away. {step}".rstrip()
    closer = change > 0
    lead = ""
    if yes_no:
        lead = "Yes, you" if closer != reverse else "No, you"
    trend = "closer" if closer else "farther"
    sentence = f"{lead or 'You'} are getting {trend}: {distance_words(abs(change))} {trend}"
    if closer:
        return f"{sentence}; it is {away} away."
    return f"{sentence}; it is {away} away. {step}".rstrip()


def answer_floor(knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState) -> str:
    """Which storey the target is on, seen from the asker's, with yes or no when the question
    proposed one ("should I go upstairs?")."""
    levels = sorted({room.level for room in knowledge.index.house.rooms})
    room = knowledge.target_room
    target = room.level if room is not None else levels[0]
    here = knowledge.index.storey_at(state.position[1])
    if here is None:
        claim = request.floor_claim
        same = None if claim is None else claim == FloorClaim.SAME
        return _yes_no(request, same, "This house has one floor, and it is on it.")
    name = storey_name(target, levels)
    if target == here:
        fact = f"It is on {name}, the floor you are on."
    else:
        way = "upstairs" if target > here else "downstairs"
        fact = f"It is on {name}: go {way}."
    claims = {
        FloorClaim.UP: target > here,
        FloorClaim.DOWN: target < here,
        FloorClaim.OTHER: target != here,
        FloorClaim.SAME: target == here,
    }
    claim = request.floor_claim
    return _yes_no(request, claims[claim] if claim is not None else None, fact)


def storey_name(level: int, levels: list[int]) -> str:
    """ "the ground floor", "the upper floor" (of two), "the middle floor", "the top floor"."""
    if level == levels[0]:
        return "the ground floor"
    if level == levels[-1]:
        return "the upper floor" if len(levels) == 2 else "the top floor"
    return "the middle floor" if len(levels) == 3 else f"floor {levels.index(level)}"


def answer_reroute(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """Where the asker is and where the target is, then the way from where it stands."""
    x, y, z = state.position
    here = knowledge.index.room_at(x, z, y)
    room = knowledge.target_room
    distance = knowledge.geodesic(x, z, y)
    if distance == math.inf:
        return CANNOT_ANSWER
    opening = f"You are in the {room_name(here)}" if here is not None else "You are here"
    there = f"in {room_phrase(knowledge, room, state)}" if room is not None else "there"
    category = knowledge.target.category
    if distance < knowledge.follower.goal_radius:
        return f"{opening}, and so is the {category}: it is right here."
    return (
        f"{opening}; the {category} is {there}, {distance_words(distance)} away. From here: "
        f"{answer_path(knowledge, state)}"
    )


def _yes_no(request: HelpRequest, claim_true: bool | None, fact: str) -> str:
    if not request.yes_no or claim_true is None:
        return fact
    return f"{'Yes' if claim_true else 'No'}. {fact}"
