"""The asker's walk read as rooms: which rooms the walked path went through, in order, how
far back along it each was left, and where the target's room stands among them.

A position counts in a room only inside the room's outline (a point in a wall or doorway
counts in none), so a walk past a doorway does not enter the room behind it. The path is
:attr:`vlln.tasks.oracle_protocol.Question.path`, the positions walked so far.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from vlln.errors import NavigationError
from vlln.oracle.answers import direction_words, distance_words, room_phrase
from vlln.oracle.knowledge import EpisodeKnowledge
from vlln.oracle.route import signed_degrees
from vlln.sim.agent import Action, AgentState
from vlln.world.model import Room

Path = tuple[tuple[float, ...], ...]
_STEP_ADVICE = {
    Action.MOVE_FORWARD: "keep going forward",
    Action.TURN_LEFT: "turn left",
    Action.TURN_RIGHT: "turn right",
}


@dataclass(frozen=True)
class Stay:
    """One uninterrupted stretch of the walk in one room."""

    room: Room
    left: float  # metres walked at its last position in the room


def walked_metres(path: Path) -> list[float]:
    """The metres walked up to each position of ``path``."""
    walked = [0.0]
    for earlier, later in itertools.pairwise(path):
        walked.append(walked[-1] + math.dist(earlier, later))
    return walked


def walked_back(path: Path, metres: float) -> tuple[float, ...] | None:
    """The position ``metres`` of walking before the last one of ``path`` (its first when it
    is shorter); None when the path never left its last position."""
    walked = 0.0
    for later, earlier in zip(path[::-1], path[-2::-1], strict=False):
        walked += math.dist(later, earlier)
        if walked >= metres:
            return earlier
    return path[0] if walked > 0.0 else None


def stays(knowledge: EpisodeKnowledge, path: Path) -> list[Stay]:
    """The rooms the walk went through, in order, one :class:`Stay` per stretch."""
    index = knowledge.index
    walked = walked_metres(path)
    points = np.array([[point[0], point[2]] for point in path], np.float64)
    rooms = np.full(len(path), -1, np.int64)
    levels: dict[int | None, list[int]] = {}
    for number, point in enumerate(path):
        levels.setdefault(index.storey_at(point[1]), []).append(number)
    for numbers in levels.values():
        rooms[numbers] = index.rooms_at(points[numbers], path[numbers[0]][1])
    found: list[Stay] = []
    for number, room_id in enumerate(rooms.tolist()):
        if room_id < 0:
            continue
        if found and found[-1].room.id == room_id:
            found[-1] = Stay(found[-1].room, walked[number])
        else:
            found.append(Stay(index.house.room(room_id), walked[number]))
    return found


def room_here(knowledge: EpisodeKnowledge, state: AgentState) -> Room | None:
    x, y, z = state.position
    return knowledge.index.room_at(x, z, y)


def ago(metres: float) -> str:
    """How far back along the walk: "about 12 meters of walking ago", "a moment ago"."""
    return "a moment ago" if metres < 1.0 else f"{distance_words(metres)} of walking ago"


def target_room_visit(
    knowledge: EpisodeKnowledge, state: AgentState, path: Path
) -> tuple[bool, float | None]:
    """Whether the asker is in the target's room now, and how many metres of walking ago it
    last was in it before (None: never)."""
    room = knowledge.target_room
    if room is None:
        return False, None
    here = room_here(knowledge, state)
    walk = stays(knowledge, path)
    now = here is not None and here.id == room.id
    if now and walk and walk[-1].room.id == room.id:
        walk = walk[:-1]
    earlier = [stay for stay in walk if stay.room.id == room.id]
    return now, walked_metres(path)[-1] - earlier[-1].left if earlier else None


def target_room_sentence(
    knowledge: EpisodeKnowledge, state: AgentState, path: Path, *, lead: bool = False
) -> str:
    """Whether the walk has been in the target's room: "You have not been in the room the bed
    is in yet: it is in the bedroom ahead of you, about 8 meters away."; with ``lead``, of its
    room, opened by yes or no ("Yes, you were in its room, ...") unless the asker is in it."""
    room = knowledge.target_room
    distance = walking(knowledge, state.position)
    if room is None or distance == math.inf:
        return ""
    away = distance_words(distance)
    now, left = target_room_visit(knowledge, state, path)
    its = "its room" if lead else f"the room the {knowledge.target.category} is in"
    if now:
        sentence = (
            f"you are in {its} now: it is in {room_phrase(knowledge, room, state, short=True)}, "
            f"{away} away."
        )
    elif left is not None:
        sentence = (
            f"you were in {its}, {room_phrase(knowledge, room, state)}, {ago(left)}; "
            f"it is {away} away, {direction(knowledge, state)}."
        )
    else:
        sentence = (
            f"you have not been in {its} yet: it is in {room_phrase(knowledge, room, state)}, "
            f"{away} away."
        )
    if lead and not now:  # "did I skip its room?" has no yes or no while in it
        return f"{'Yes' if left is not None else 'No'}, {sentence}"
    return sentence[0].upper() + sentence[1:]


def walking(knowledge: EpisodeKnowledge, point: tuple[float, ...]) -> float:
    """Walking distance from ``point`` to the target's view points."""
    x, y, z = point
    return knowledge.geodesic(x, z, y)


def direction(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """Where the target lies from the asker's heading: "ahead of you", "to your left"."""
    return direction_words(signed_degrees(knowledge, state))


def advice(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The next step toward the target: "To get closer, turn left."."""
    try:
        action = knowledge.follower.next_action(state)
    except NavigationError:
        return ""
    step = _STEP_ADVICE.get(action)
    return f"To get closer, {step}." if step else "You are there."
