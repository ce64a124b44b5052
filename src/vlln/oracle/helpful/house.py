"""Answers from the house's objects: how many of a category there are and where, what stands
around the target, and whether it is near a window.

Windows are the house's ``window`` instances (scans) and its window coverings: generated
houses hang curtains and blinds on outer walls only, where the windows would be
(:data:`vlln.world.generator.furnishing.WINDOW_COVERINGS`).
"""

from __future__ import annotations

import re
from collections import defaultdict
from functools import lru_cache

from vlln.oracle.answers import distance_words, room_phrase
from vlln.oracle.classifier.entities import object_names
from vlln.oracle.helpful.progress import storey_name
from vlln.oracle.helpful.recognise import HelpRequest
from vlln.oracle.helpful.view import candidates_in_view, counted, plural
from vlln.oracle.knowledge import EpisodeKnowledge, object_phrase, room_name
from vlln.sim.agent import AgentState
from vlln.tasks.oracle_protocol import Question
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.generator.furnishing import WINDOW_COVERINGS
from vlln.world.model import ObjectInstance, Room

NEIGHBOUR_RADIUS = 1.5  # m between boxes: what stands "around" the target
NEIGHBOURS_NAMED = 4
RIGHT_BESIDE = 0.3  # m between boxes: "right beside it"
WINDOW_NEAR = 1.5  # m between the target's box and a window's: "near a window"
_MODAL_CAN = re.compile(r"\bcan (?=(i|you|we|they|it)\b)")
_STOREY_WORDS = re.compile(r"\b(upstairs|downstairs|floors?|storeys?|stor(y|ies)|levels?)\b")


def answer_count(knowledge: EpisodeKnowledge, request: HelpRequest, question: Question) -> str:
    """How many instances of the category the question names (else the target's) the house
    has, by room: "There are 3 chairs in this house: 2 in the kitchen, 1 in the study."; by
    floor too when it names floors; those in view when it asks what the asker sees."""
    target = knowledge.target
    house = knowledge.index.house
    text = _MODAL_CAN.sub("", request.text)  # "how many can I see": "can" is no object here
    named = [canonical_category(m.group(1)) for m in _catalogue_pattern().finditer(text)]
    category = next((name for name in named if name != target.category), target.category)
    instances = house.instances_of(category)
    if request.in_view:
        return _count_in_view(knowledge, category, question)
    if not instances:
        return f"There is no {category} in this house."
    sentence = _count_in_house(knowledge, category, instances, question.state)
    if _STOREY_WORDS.search(text):
        return f"{sentence} {_by_floor(knowledge, instances)}"
    return sentence


def _count_in_house(
    knowledge: EpisodeKnowledge, category: str, instances: list[ObjectInstance], state: AgentState
) -> str:
    target = knowledge.target
    by_type: dict[str, list[ObjectInstance]] = defaultdict(list)
    for instance in instances:
        room = _room(knowledge, instance)
        by_type[room_name(room) if room is not None else "open area"].append(instance)
    if len(instances) == 1:
        (name, group), *_ = by_type.items()
        return f"There is only one {category} in this house, {_rooms(knowledge, name, group)}."
    places = [
        f"{len(group)} {_rooms(knowledge, name, group)}" for name, group in sorted(by_type.items())
    ]
    sentence = f"There are {counted(len(instances), category)} in this house: {', '.join(places)}."
    room = knowledge.target_room
    if category != target.category or room is None:
        return sentence
    return f"{sentence} The one I mean is in {room_phrase(knowledge, room, state)}."


def _by_floor(knowledge: EpisodeKnowledge, instances: list[ObjectInstance]) -> str:
    """ "By floor: 2 on the ground floor, 1 on the upper floor." (one-floor houses say so)."""
    levels = sorted({room.level for room in knowledge.index.house.rooms})
    if len(levels) < 2:
        return "This house has one floor."
    on: dict[int, int] = defaultdict(int)
    for instance in instances:
        room = _room(knowledge, instance)
        on[room.level if room is not None else levels[0]] += 1
    parts = [f"{on[level]} on {storey_name(level, levels)}" for level in levels]
    return f"By floor: {', '.join(parts)}."


def _count_in_view(knowledge: EpisodeKnowledge, category: str, question: Question) -> str:
    """How many of ``category`` the asker sees, and which is the target among them."""
    in_view = candidates_in_view(knowledge, question.state, question.frame, category)
    seen = [candidate.instance.id for candidate in in_view]
    if not seen:
        return f"No {category} is in your view."
    verb = "is" if len(seen) == 1 else "are"
    sentence = f"{counted(len(seen), category).capitalize()} {verb} in your view."
    if category != knowledge.target.category:
        return sentence
    if knowledge.target.id not in seen:
        return f"{sentence} The one I mean is not among them."
    return f"{sentence} One of them is the one I mean."


def _rooms(knowledge: EpisodeKnowledge, name: str, group: list[ObjectInstance]) -> str:
    """Where instances in rooms named ``name`` are: "in the kitchen" (the house's only
    kitchen), "in a bedroom", "in 2 bedrooms"."""
    rooms = {instance.room_id for instance in group}
    room = _room(knowledge, group[0])
    if room is not None and knowledge.index.same_type_rooms(room) == 1:
        return f"in the {name}"
    if len(rooms) == 1:
        return f"in {'an' if name[0] in 'aeiou' else 'a'} {name}"
    return f"in {len(rooms)} {plural(name)}"


def answer_neighbourhood(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """The room, and the objects within :data:`NEIGHBOUR_RADIUS` of the target, nearest
    first: what it stands on or next to, and how far the others are."""
    target = knowledge.target
    index = knowledge.index
    room = knowledge.target_room
    where = f"It is in {room_phrase(knowledge, room, state, short=True)}" if room else "It is"
    near = sorted(
        (target.box.distance_to(other.box), other.id, other)
        for other in index.house.instances
        if other.id != target.id and "ceiling" not in other.category
    )
    near = [item for item in near if item[0] <= NEIGHBOUR_RADIUS][:NEIGHBOURS_NAMED]
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


def joined(items: list[str]) -> str:
    """ "a", "a and b", "a, b and c"."""
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


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
    room = _room(knowledge, window)
    there = f", in {room_phrase(knowledge, room, state)}" if room is not None else ""
    return f"No, the nearest window is {distance_words(gap)} from it: {what}{there}."


def _room(knowledge: EpisodeKnowledge, instance: ObjectInstance) -> Room | None:
    try:
        return knowledge.index.house.room(instance.room_id)
    except KeyError:
        x, _, z = instance.box.center
        return knowledge.index.room_at(x, z, instance.box.min[1])


@lru_cache(maxsize=1)
def _catalogue_pattern() -> re.Pattern[str]:
    """Finds catalogue names and aliases, in the singular or plural, longest first."""
    names = "|".join(re.escape(n) for n in sorted(object_names(), key=len, reverse=True))
    return re.compile(rf"\b({names})(?:s|es)?\b")
