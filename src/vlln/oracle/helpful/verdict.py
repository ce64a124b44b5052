"""A verdict on the walk so far: "was going into the laundry a mistake?", "did I detour a
lot?", "how much closer am I than at the start?".

Such a question wants the path judged, not the distance left: whether its last stretch took
the asker closer or farther, how much closer it is than where it started, and how much of its
walk was detour (metres walked beyond the metres it gained). Where it names rooms it walked
into, whether the target's room is among them settles it.
"""

from __future__ import annotations

import math

from vlln.oracle.answers import distance_words
from vlln.oracle.helpful.path import Path, advice, walked_back, walked_metres, walking
from vlln.oracle.helpful.recognise import HelpRequest
from vlln.oracle.knowledge import EpisodeKnowledge, room_name
from vlln.oracle.route import CANNOT_ANSWER
from vlln.sim.agent import AgentState

RECENT_WALK = 5.0  # m walked back along the path: the stretch "that" turn or room was
CHANGE = 0.5  # m of walking distance that count as closer or farther
DETOUR_SLACK = 3.0  # m walked beyond the metres gained that still count as the short way


def answer_route(
    knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState, path: Path
) -> str:
    """The verdict (module doc), opened by yes or no when the question proposes one: a wrong
    turn or detour (``request.reverse``), or progress."""
    now = walking(knowledge, state.position)
    start = walking(knowledge, path[0])
    if now == math.inf or start == math.inf:
        return CANNOT_ANSWER
    walked = walked_metres(path)[-1]
    gained = start - now
    detour = walked - max(gained, 0.0)
    recent = _recent(knowledge, path)
    named = _named_room(knowledge, request)
    if named is not None:
        bad = not named
    elif "detour" in request.text or "long way" in request.text:
        bad = detour > DETOUR_SLACK
    else:
        bad = recent < -CHANGE or (recent <= CHANGE and gained < CHANGE)
    sentences = [_recent_sentence(recent), _overall(start, now, gained)]
    if walked > 0.0:
        sentences.append(_detour_sentence(walked, detour))
    if named is not None:
        sentences.insert(0, _named_sentence(knowledge, named))
    text = " ".join(s for s in sentences if s)
    if request.yes_no:
        lead = "Yes" if bad == request.reverse else "No"
        text = f"{lead}. {text}"
    if bad:
        text = f"{text} {advice(knowledge, state)}".rstrip()
    return text


def _recent(knowledge: EpisodeKnowledge, path: Path) -> float:
    """Metres of walking distance gained over the last :data:`RECENT_WALK` metres walked."""
    back = walked_back(path, RECENT_WALK) or path[-1]
    return walking(knowledge, back) - walking(knowledge, path[-1])


def _recent_sentence(recent: float) -> str:
    if abs(recent) < CHANGE:
        return "Your last few meters kept you about as far from it."
    trend = "closer" if recent > 0 else "farther"
    return f"Your last few meters took you {trend}: {distance_words(abs(recent))} {trend}."


def _overall(start: float, now: float, gained: float) -> str:
    if abs(gained) < CHANGE:
        return f"You are about as far as at the start, {distance_words(now)} away."
    trend = "closer" if gained > 0 else "farther"
    return (
        f"Since the start you are {distance_words(abs(gained))} {trend}: it was "
        f"{distance_words(start)} away and is {distance_words(now)} away now."
    )


def _detour_sentence(walked: float, detour: float) -> str:
    if detour <= DETOUR_SLACK:
        return f"You walked {distance_words(walked)}, about the shortest way."
    return (
        f"You walked {distance_words(walked)}, a detour of {distance_words(detour)} beyond "
        "what you gained."
    )


def _named_room(knowledge: EpisodeKnowledge, request: HelpRequest) -> bool | None:
    """Whether the rooms the question names ("going into the laundry") hold the target's room;
    None when it names none."""
    room = knowledge.target_room
    if not request.rooms or room is None:
        return None
    return room_name(room) in request.rooms or room.type in request.rooms


def _named_sentence(knowledge: EpisodeKnowledge, named: bool) -> str:
    room = knowledge.target_room
    category = knowledge.target.category
    if room is None:
        return ""
    where = f"the {room_name(room)}"
    if named:
        return f"The {category} is in {where}."
    return f"The {category} is not there: it is in {where}."
