"""Answers from the house's objects: how many of a category there are, where, and how many
of them the asker sees, has in its room or walked past.

The category counted is the one the question names, else the target's; "can" is the object
only where it reads as a noun ("a can", "cans"), never the verb of "how many can I see?".
What the asker walked past is what stands in the rooms its walk went through (:mod:`.path`).
"""

from __future__ import annotations

import re
from collections import defaultdict
from functools import lru_cache

from vlln.oracle.answers import room_phrase, with_article
from vlln.oracle.classifier.entities import object_names
from vlln.oracle.helpful.path import room_here, stays
from vlln.oracle.helpful.progress import storey_name
from vlln.oracle.helpful.recognise import CountScope, HelpRequest
from vlln.oracle.helpful.view import candidates_in_view, counted, plural
from vlln.oracle.knowledge import EpisodeKnowledge, room_name
from vlln.sim.agent import AgentState
from vlln.tasks.oracle_protocol import Question
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.model import ObjectInstance

_STOREY_WORDS = re.compile(r"\b(upstairs|downstairs|floors?|storeys?|stor(y|ies)|levels?)\b")
# A count of what the asker sees that also asks about the rest: "more than the ones I see?".
_BEYOND_VIEW = re.compile(r"\b(more|other|others|only|just|else|besides|total|all|house)\b")
# Words before "can" that make it the object ("a can", "the paint can"), not the verb.
_CAN_NOUNS = "a the one any no this that each every empty trash garbage paint tin soda watering"
_CAN_NOUN_AFTER = frozenset(_CAN_NOUNS.split())


def answer_count(knowledge: EpisodeKnowledge, request: HelpRequest, question: Question) -> str:
    """How many instances of the category the question names (else the target's) the house
    has, by room: "There are 3 chairs in this house: 2 in the kitchen, 1 in the study."; by
    floor too when it names floors; before that, those in view, in the asker's room or in
    the rooms it walked through when it asks about those."""
    text = request.text
    category = _counted_category(knowledge, text)
    instances = knowledge.index.house.instances_of(category)
    state = question.state
    parts = []
    if CountScope.VIEW in request.scopes:
        parts.append(_count_in_view(knowledge, category, question))
    if CountScope.ROOM in request.scopes:
        parts.append(_count_in_room(knowledge, category, instances, state))
    if CountScope.WALKED in request.scopes:  # says where every one of them is
        path = question.path or (state.position,)
        parts.append(_count_walked(knowledge, category, instances, state, path))
        return " ".join(parts)
    if CountScope.VIEW in request.scopes and not _BEYOND_VIEW.search(text) and len(parts) == 1:
        return parts[0]
    if not instances:
        parts.append(f"There is no {category} in this house.")
    else:
        parts.append(_count_in_house(knowledge, category, instances, state))
        if _STOREY_WORDS.search(text):
            parts.append(_by_floor(knowledge, instances))
    return " ".join(parts)


def _counted_category(knowledge: EpisodeKnowledge, text: str) -> str:
    """The category a count names, the target's when it names none but the target's."""
    target = knowledge.target.category
    named = []
    for match in _catalogue_pattern().finditer(text):
        before = text[: match.start()].split()[-1:]
        if match.group(0) == "can" and not set(before) & _CAN_NOUN_AFTER:
            continue  # "how many can I see?", "couches can be seen", "the one I can see"
        named.append(canonical_category(match.group(1)))
    return next((name for name in named if name != target), target)


def _count_in_room(
    knowledge: EpisodeKnowledge, category: str, instances: list[ObjectInstance], state: AgentState
) -> str:
    """ "There are two plants in this living room." (the room the asker stands in)."""
    here = room_here(knowledge, state)
    if here is None:
        return "You are outside the house's rooms."
    inside = [instance for instance in instances if instance.room_id == here.id]
    where = f"in this {room_name(here)}"
    if not inside:
        return f"There is no {category} {where}."
    verb = "is" if len(inside) == 1 else "are"
    return f"There {verb} {counted(len(inside), category)} {where}."


def _count_walked(
    knowledge: EpisodeKnowledge,
    category: str,
    instances: list[ObjectInstance],
    state: AgentState,
    path: tuple[tuple[float, ...], ...],
) -> str:
    """How many stand in the rooms the walk went through, and where the rest are."""
    walked = {stay.room.id for stay in stays(knowledge, path)}
    passed = [instance for instance in instances if instance.room_id in walked]
    rest = [instance for instance in instances if instance.room_id not in walked]
    if not passed:
        sentence = f"No {category} is in the rooms you have walked through."
    else:
        verb = "is" if len(passed) == 1 else "are"
        sentence = (
            f"{counted(len(passed), category).capitalize()} {verb} in the rooms you have walked "
            f"through: {_places(knowledge, passed)}."
        )
    if rest:
        verb = "is" if len(rest) == 1 else "are"
        sentence += (
            f" {counted(len(rest), category).capitalize()} {verb} in rooms you have not been in: "
            f"{_places(knowledge, rest)}."
        )
    room = knowledge.target_room
    if category != knowledge.target.category or room is None:
        return sentence
    if knowledge.target in passed:
        where = room_phrase(knowledge, room, state, short=True)
        return f"{sentence} The one I mean is one of those, in {where}."
    where = room_phrase(knowledge, room, state)
    return f"{sentence} The one I mean is in {where}, where you have not been yet."


def _places(knowledge: EpisodeKnowledge, instances: list[ObjectInstance]) -> str:
    """ "1 in the kitchen, 2 in 2 bedrooms"."""
    by_type: dict[str, list[ObjectInstance]] = defaultdict(list)
    for instance in instances:
        room = knowledge.index.room_of(instance)
        by_type[room_name(room) if room is not None else "open area"].append(instance)
    return ", ".join(
        f"{len(group)} {_rooms(knowledge, name, group)}" for name, group in sorted(by_type.items())
    )


def _count_in_house(
    knowledge: EpisodeKnowledge, category: str, instances: list[ObjectInstance], state: AgentState
) -> str:
    target = knowledge.target
    by_type: dict[str, list[ObjectInstance]] = defaultdict(list)
    for instance in instances:
        room = knowledge.index.room_of(instance)
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
        room = knowledge.index.room_of(instance)
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
    room = knowledge.index.room_of(group[0])
    if room is not None and knowledge.index.same_type_rooms(room) == 1:
        return f"in the {name}"
    if len(rooms) == 1:
        return f"in {with_article(name)}"
    return f"in {len(rooms)} {plural(name)}"


@lru_cache(maxsize=1)
def _catalogue_pattern() -> re.Pattern[str]:
    """Finds catalogue names and aliases, in the singular or plural, longest first."""
    names = "|".join(re.escape(n) for n in sorted(object_names(), key=len, reverse=True))
    return re.compile(rf"\b({names})(?:s|es)?\b")
