"""Answers about the walk so far: whether the asker has been here before, in a named room or
in the target's room, whether it is back where it started or walking over its own tracks,
which rooms it has been through, and whether it is in the target's part of the house.

The rooms come from the walked path (:mod:`.path`); every answer ends with where the target's
room stands against the walk, so "have I been here before?" also says whether to look on.
"""

from __future__ import annotations

import math

from vlln.oracle.answers import (
    CLOSE_RADIUS,
    distance_words,
    joined,
    room_phrase,
    with_article,
)
from vlln.oracle.helpful.path import (
    Path,
    Stay,
    advice,
    ago,
    room_here,
    stays,
    target_room_sentence,
    walked_metres,
    walking,
)
from vlln.oracle.helpful.progress import answer_closer
from vlln.oracle.helpful.recognise import HelpRequest, PathTopic
from vlln.oracle.helpful.verdict import answer_route
from vlln.oracle.helpful.view import number_word, plural
from vlln.oracle.knowledge import EpisodeKnowledge, room_name
from vlln.oracle.route import CANNOT_ANSWER
from vlln.sim.agent import AgentState
from vlln.world.model import Room

REVISIT_NEAR = 0.75  # m: the asker stands this close to where it stood before ...
REVISIT_WALK = 3.0  # m: ... at least this much walking ago: it is back on its own tracks


def answer_visited(
    knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState, path: Path
) -> str:
    """The answer to a question about the walk (module doc), by its :class:`PathTopic`."""
    if walking(knowledge, state.position) == math.inf:
        return CANNOT_ANSWER
    walk = stays(knowledge, path)
    here = room_here(knowledge, state)
    topic = request.topic
    if topic == PathTopic.TARGET_ROOM:
        return target_room_sentence(knowledge, state, path, lead=True)
    if topic == PathTopic.AREA:
        return _area(knowledge, request, state)
    if topic == PathTopic.ROUTE:
        return answer_route(knowledge, request, state, path)
    if topic == PathTopic.RETRACING:
        return _retracing(knowledge, state, path, walk, here)
    if topic == PathTopic.START:
        fact = _start(walk, here)
    elif topic == PathTopic.ROOMS:
        fact = _rooms(knowledge, walk, here)
    elif topic == PathTopic.NAMED:
        fact = _named(knowledge, request.rooms, walk, here, walked_metres(path)[-1])
    else:
        fact = _here(request, walk, here, walked_metres(path)[-1])
    return f"{fact} {target_room_sentence(knowledge, state, path)}".rstrip()


def _here(request: HelpRequest, walk: list[Stay], here: Room | None, total: float) -> str:
    """ "Yes, you were in this kitchen before, ..." or "No, this is the first time you are
    in this bedroom."; yes and no swap for "is this the first time?"."""
    if here is None:
        return "You are outside the house's rooms."
    name = room_name(here)
    before = _left(walk, here)
    if all(stay.room.id == here.id for stay in walk):
        return f"You started in this {name} and have not left it yet."
    if before:
        fact = f"you were in this {name} before, {ago(total - before[-1].left)}."
    else:
        fact = f"this is the first time you are in this {name}."
    return f"{'Yes' if bool(before) != request.reverse else 'No'}, {fact}"


def _left(walk: list[Stay], here: Room) -> list[Stay]:
    """The earlier stays in ``here``'s room, which the walk left (the stay it is in now, in
    its room, is no earlier one; in a doorway it may stand in none)."""
    if walk and walk[-1].room.id == here.id:
        walk = walk[:-1]
    return [stay for stay in walk if stay.room.id == here.id]


def _named(
    knowledge: EpisodeKnowledge,
    types: tuple[str, ...],
    walk: list[Stay],
    here: Room | None,
    total: float,
) -> str:
    """Whether the walk went through a room of the named types ("have I been in the
    kitchen?")."""
    house = knowledge.index.house
    rooms = [room for room in house.rooms if room.type in types]
    name = " or ".join(dict.fromkeys(room_name(room) for room in rooms)) or " or ".join(types)
    if not rooms:
        return f"This house has no {name}."
    if here is not None and here.type in types:
        return f"Yes, you are in the {room_name(here)} now."
    visits = [stay for stay in walk if stay.room.type in types]
    if visits:
        return f"Yes, you were in the {room_name(visits[-1].room)} {ago(total - visits[-1].left)}."
    article = "the" if len(rooms) == 1 else "a"
    return f"No, you have not been in {article} {name} yet."


def _start(walk: list[Stay], here: Room | None) -> str:
    """Whether the asker is in the room its walk started in."""
    if not walk or here is None:
        return "You have not walked through any room yet."
    first = walk[0].room
    if first.id == here.id:
        again = "" if len(walk) == 1 else ", and you have come back to it"
        return f"Yes, you are in the {room_name(first)} you started in{again}."
    return f"No, you started in the {room_name(first)}; now you are in the {room_name(here)}."


def _rooms(knowledge: EpisodeKnowledge, walk: list[Stay], here: Room | None) -> str:
    """The rooms walked through, in order, and the rooms of the storey not yet been in."""
    seen = list({stay.room.id: stay.room for stay in walk}.values())
    if not seen:
        return "You have not walked through any room yet."
    level = here.level if here is not None else seen[-1].level
    rooms = knowledge.index.house.rooms
    on_storey = [room for room in rooms if room.level == level]
    several = len({room.level for room in rooms}) > 1
    where = "this floor's" if several else "this house's"
    sentence = (
        f"You have been in {len(seen)} of {where} {len(on_storey)} rooms so far: "
        f"{_names(knowledge, seen)}"
    )
    if here is not None and here.id == seen[-1].id:
        sentence += ", where you are now"
    elif here is not None:
        sentence += f", and you are in the {room_name(here)} now"
    unseen = [room for room in on_storey if room.id not in {r.id for r in seen}]
    if unseen:
        sentence += f". Not yet: {_names(knowledge, unseen, {room.type for room in seen})}"
    return f"{sentence}."


def _names(knowledge: EpisodeKnowledge, rooms: list[Room], seen: set[str] | None = None) -> str:
    """ "the kitchen, a bedroom and two bathrooms", in the order first met; "the other
    bedroom" for a room of a type already named in ``seen``."""
    counts: dict[str, list[Room]] = {}
    for room in rooms:
        counts.setdefault(room.type, []).append(room)
    parts = []
    for group in counts.values():
        name = room_name(group[0])
        other = "other " if seen and group[0].type in seen else ""
        if len(group) > 1:
            parts.append(f"{number_word(len(group))} {other}{plural(name)}")
        elif other or knowledge.index.same_type_rooms(group[0]) == 1:
            parts.append(f"the {other}{name}")
        else:
            parts.append(with_article(name))
    return joined(parts)


def _retracing(
    knowledge: EpisodeKnowledge,
    state: AgentState,
    path: Path,
    walk: list[Stay],
    here: Room | None,
) -> str:
    """ "Am I going in circles?": yes when the asker stands where it stood
    :data:`REVISIT_WALK` or more of walking ago, or is back in a room it had left; then
    whether it is getting closer, and where the target's room is."""
    walked = walked_metres(path)
    total = walked[-1]
    position = state.position
    back = [
        total - metres
        for point, metres in zip(path, walked, strict=True)
        if total - metres >= REVISIT_WALK and math.dist(point, position) <= REVISIT_NEAR
    ]
    before = _left(walk, here) if here is not None else []
    if back:
        fact = f"Yes, you are walking over your own tracks: you stood here {ago(min(back))}."
    elif before:
        name = room_name(before[-1].room)
        fact = f"Yes, you are back in this {name}: you left it {ago(total - before[-1].left)}."
    else:
        fact = "No, you are not going over ground you walked before."
    trend = answer_closer(knowledge, state, path, yes_no=False)
    return f"{fact} {target_room_sentence(knowledge, state, path)} {trend}".rstrip()


def _area(knowledge: EpisodeKnowledge, request: HelpRequest, state: AgentState) -> str:
    """ "Am I in the wrong part of the house?": the right part is the target's room, or
    within :data:`vlln.oracle.answers.CLOSE_RADIUS` of walking of the target."""
    room = knowledge.target_room
    here = room_here(knowledge, state)
    distance = walking(knowledge, state.position)
    away = distance_words(distance)
    near = (room is not None and here is not None and here.id == room.id) or (
        distance <= CLOSE_RADIUS
    )
    lead = "Yes" if near != request.reverse else "No"  # "wrong part?" asks the reverse
    there = f"in {room_phrase(knowledge, room, state)}" if room is not None else "there"
    if near:
        return f"{lead}, you are in the right part: it is {there}, {away} away."
    return (
        f"{lead}, it is not around here: it is {there}, {away} away. {advice(knowledge, state)}"
    ).rstrip()
