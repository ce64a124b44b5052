"""Answers about what is around the target: what stands near it, what is on top of it, under
it, in front of it, behind it or on the wall near it, and whether it is near a window.

The relation graph (:mod:`vlln.world.relations`) knows "on", "under", "above", "next to"
and "near"; front and back are read off the target's heading, a model's front being the
side it faces (:mod:`vlln.world.generator.poses`). Windows are the house's ``window``
instances (scans) and its window coverings: generated houses hang curtains and blinds on
outer walls only, where the windows would be
(:data:`vlln.world.generator.furnishing.WINDOW_COVERINGS`).
"""

from __future__ import annotations

import math

from vlln.oracle.answers import distance_words, joined, room_phrase
from vlln.oracle.knowledge import EpisodeKnowledge, object_phrase
from vlln.sim.agent import AgentState
from vlln.world.generator.furnishing import WINDOW_COVERINGS
from vlln.world.model import ObjectInstance

NEIGHBOUR_RADIUS = 1.5  # m between boxes: what stands "around" the target
NEIGHBOURS_NAMED = 4
RIGHT_BESIDE = 0.3  # m between boxes: "right beside it"
WINDOW_NEAR = 1.5  # m between the target's box and a window's: "near a window"
WALL_NEAR = 2.0  # m between boxes: what hangs "on the wall near it"
FACE_SLACK = 0.1  # m: how far into the target's box a thing "in front of it" may reach
# How a placement stands the target, when nothing in the house holds it up.
_STANDS = {
    "on the floor": "it stands on the floor",
    "against the wall": "it stands on the floor, against the wall",
    "at the table": "it stands on the floor, at the table",
    "in the corner": "it stands on the floor, in the corner",
    "on the wall": "it hangs on the wall",
    "on the ceiling": "it hangs from the ceiling",
}
_ON_WALL = {"on the wall": "hangs on", "against the wall": "stands against"}
_STACKED = ("on", "under", "above")  # relations of things on or under it, not beside it


def answer_neighbourhood(
    knowledge: EpisodeKnowledge, state: AgentState, relation: str | None = None
) -> str:
    """What the question asks about the target's surroundings: the ``relation`` ("above",
    "under", "support", "front", "behind", "wall") when the house knows it, and the objects
    around it (:func:`surroundings`) when it knows of none there or none was asked."""
    around = surroundings(knowledge, state)
    related = _RELATED.get(relation) if relation else None
    if related is None:
        return around
    found, missing = related(knowledge)
    return found or f"{missing} {around}"


def surroundings(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The room, and the objects within :data:`NEIGHBOUR_RADIUS` of the target, nearest
    first: what it stands on or next to, and how far the others are."""
    target = knowledge.target
    index = knowledge.index
    room = knowledge.target_room
    where = f"It is in {room_phrase(knowledge, room, state, short=True)}" if room else "It is"
    near = [item for item in _near(knowledge) if item[0] <= NEIGHBOUR_RADIUS][:NEIGHBOURS_NAMED]
    if not near:
        return f"{where}; nothing else stands within {NEIGHBOUR_RADIUS:g} meters of it."
    own = {r.object: r.word for r in index.relations.get(target.id, [])}
    theirs = {r.subject: r.word for r in index.relations_to.get(target.id, [])}
    related: dict[str, list[str]] = {}  # by relation word, nearest first
    others = []
    for gap, _, other in near:
        phrase = object_phrase(other)
        if other.id in own:
            related.setdefault(own[other.id], []).append(phrase)
        elif other.id in theirs:
            others.append(f"{phrase} is {theirs[other.id]} it")
        elif gap < RIGHT_BESIDE:
            others.append(f"{phrase} is right beside it")
        else:
            others.append(f"{phrase} is {distance_words(gap)} away")
    sentence = where + "".join(f", {word} {joined(phrases)}" for word, phrases in related.items())
    if not others:
        return f"{sentence}."
    rest = "; ".join(others)
    return f"{sentence}. {rest[0].upper()}{rest[1:]}."


Found = tuple[str, str]  # the answer when the house knows some; the words when it knows none
Part = tuple[float, int, str]  # the gap to the target, the other's id, what it is to the target


def _above(knowledge: EpisodeKnowledge) -> Found:
    """What is on top of or above the target."""
    index, target = knowledge.index, knowledge.target
    parts = [
        (r.distance, r.subject, f"{r.word} it")
        for r in index.relations_to.get(target.id, [])
        if r.word in ("on", "above")
    ]
    parts += [
        (r.distance, r.object, "above it")
        for r in index.relations.get(target.id, [])
        if r.word == "under"
    ]
    return _sentences(knowledge, parts), "Nothing is on top of it."


def _under(knowledge: EpisodeKnowledge) -> Found:
    """What is under the target: what it rests on or hangs over, what stands beneath it."""
    index, target = knowledge.index, knowledge.target
    own = [r for r in index.relations.get(target.id, []) if r.word in ("on", "above")]
    parts = [
        (r.distance, r.subject, "under it")
        for r in index.relations_to.get(target.id, [])
        if r.word == "under"
    ]
    resting = "; ".join(f"it is {r.word} {object_phrase(index.instances[r.object])}" for r in own)
    found = "; ".join(text for text in (resting, _listed(knowledge, parts)) if text)
    if not found:
        return "", f"Nothing is under it: {_stands(knowledge)}."
    return f"{found[0].upper()}{found[1:]}.", ""


def _support(knowledge: EpisodeKnowledge) -> Found:
    """What the target rests on: the object it is on, else the floor, wall or ceiling."""
    index, target = knowledge.index, knowledge.target
    own = [r for r in index.relations.get(target.id, []) if r.word == "on"]
    if own:
        return f"It is on {joined([object_phrase(index.instances[r.object]) for r in own])}.", ""
    stands = _stands(knowledge)
    return f"{stands[0].upper()}{stands[1:]}.", ""


def _stands(knowledge: EpisodeKnowledge) -> str:
    """ "it stands on the floor, against the wall", "it hangs on the wall"."""
    placement = knowledge.target.attributes.placement
    return _STANDS.get(placement, f"it is {placement}" if placement else "it stands on the floor")


def _facing(knowledge: EpisodeKnowledge, side: float) -> list[Part]:
    """Objects around the target beyond its front face (``side`` 1) or its back face (-1),
    and across from it, nearest first; not those on it or under it."""
    target = knowledge.target
    box = target.box
    fx, fz = math.sin(target.yaw) * side, math.cos(target.yaw) * side
    axis, across = (0, 2) if abs(fx) >= abs(fz) else (2, 0)
    ahead = (fx if axis == 0 else fz) > 0
    face = box.max[axis] if ahead else box.min[axis]
    low, high = box.min[across] - FACE_SLACK, box.max[across] + FACE_SLACK
    index = knowledge.index
    stacked = {r.object for r in index.relations.get(target.id, []) if r.word in _STACKED}
    stacked |= {r.subject for r in index.relations_to.get(target.id, []) if r.word in _STACKED}
    found = []
    for gap, _, other in _near(knowledge):
        if gap > NEIGHBOUR_RADIUS or other.id in stacked:
            continue
        near, far = other.box.min[axis], other.box.max[axis]
        beyond = near >= face - FACE_SLACK if ahead else far <= face + FACE_SLACK
        if beyond and other.box.max[across] > low and other.box.min[across] < high:
            found.append((gap, other.id, "in front of it" if side > 0 else "behind it"))
    return found


def _front(knowledge: EpisodeKnowledge) -> Found:
    return _sentences(knowledge, _facing(knowledge, 1.0)), "Nothing stands right in front of it."


def _behind(knowledge: EpisodeKnowledge) -> Found:
    placement = knowledge.target.attributes.placement
    found = _sentences(knowledge, _facing(knowledge, -1.0))
    if placement in _ON_WALL:
        wall = f"The wall is behind it: it {_ON_WALL[placement]} the wall."
        return f"{wall} {found}".rstrip(), ""
    return found, "Nothing stands right behind it."


def _wall(knowledge: EpisodeKnowledge) -> Found:
    """What hangs on a wall within :data:`WALL_NEAR` of the target."""
    index, target = knowledge.index, knowledge.target
    above = {r.subject for r in index.relations_to.get(target.id, []) if r.word == "above"}
    hung = [
        other
        for gap, _, other in _near(knowledge)
        if gap <= WALL_NEAR and other.attributes.placement == "on the wall"
    ]
    names = [
        object_phrase(other) + (" (above it)" if other.id in above else "")
        for other in hung[:NEIGHBOURS_NAMED]
    ]
    if not names:
        return "", "Nothing hangs on the wall near it."
    return f"On the wall near it: {joined(names)}.", ""


_RELATED = {
    "above": _above,
    "under": _under,
    "support": _support,
    "front": _front,
    "behind": _behind,
    "wall": _wall,
}


def _sentences(knowledge: EpisodeKnowledge, parts: list[Part]) -> str:
    """The parts as one sentence (:func:`_listed`); empty when there are none."""
    text = _listed(knowledge, parts)
    return f"{text[0].upper()}{text[1:]}." if text else ""


def _listed(knowledge: EpisodeKnowledge, parts: list[Part]) -> str:
    """The objects, each once, nearest first, grouped by what they are to the target: "the
    white laptop and the yellow magazine are on it; the lamp is above it"."""
    named: dict[int, tuple[float, str]] = {}
    for gap, other, what in parts:
        if other not in named:
            named[other] = (gap, what)
    chosen = sorted(named.items(), key=lambda item: (item[1][0], item[0]))[:NEIGHBOURS_NAMED]
    groups: dict[str, list[str]] = {}
    for other, (_, what) in chosen:
        groups.setdefault(what, []).append(object_phrase(knowledge.index.instances[other]))
    return "; ".join(f"{joined(names)} {_be(names)} {what}" for what, names in groups.items())


def _be(names: list[str]) -> str:
    """ "is" for one thing, "are" for several or a plural name ("the beige blinds")."""
    plural = len(names) > 1 or (names[0].endswith("s") and not names[0].endswith("ss"))
    return "are" if plural else "is"


def _near(knowledge: EpisodeKnowledge) -> list[tuple[float, int, ObjectInstance]]:
    """Every other object by the gap between its box and the target's, nearest first."""
    target = knowledge.target
    return sorted(
        (target.box.distance_to(other.box), other.id, other)
        for other in knowledge.index.house.instances
        if other.id != target.id and "ceiling" not in other.category
    )


def answer_window(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """Whether the target is within :data:`WINDOW_NEAR` of a window, and of which."""
    target = knowledge.target
    windows = [
        inst
        for inst in knowledge.index.house.instances
        if inst.category == "window" or inst.category in WINDOW_COVERINGS
    ]
    if not windows:
        return "No, I know of no window in this house."
    gap, _, window = min((target.box.distance_to(w.box), w.id, w) for w in windows)
    if window.id == target.id:
        return "Yes, it hangs at a window itself."
    what = "a window" if window.category == "window" else f"the window with {object_phrase(window)}"
    if gap <= WINDOW_NEAR:
        return f"Yes, it is near a window: {distance_words(gap)} from {what}."
    room = knowledge.index.room_of(window)
    there = f", in {room_phrase(knowledge, room, state)}" if room is not None else ""
    return f"No, the nearest window is {distance_words(gap)} from it: {what}{there}."
