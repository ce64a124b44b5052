"""Attribute and Other answers: facts about the target and about the asker, from the house.

Attribute answers say exactly what was asked ("It is red.", "It is made of wood.", "It is in
the kitchen.", "It is next to the white sofa."), and a plain "I don't know." when the house
does not record it. A yes/no question that names a value ("is it red?") gets "Yes" or "No"
with the true value. Rooms are named so that the agent can tell them apart: "this room" when
it stands in it, and a direction when the house has several rooms of that type.

Other answers use privileged knowledge of the agent's state: the room it is in, the walking
distance to the target, whether it is close (within the 3 m oracle-success radius) or going
the right way, whether the target is in view. Anything else gets the reference's fixed
refusal, :data:`CANNOT_ANSWER`.
"""

from __future__ import annotations

import math
import re

import numpy as np

from vlln.errors import NavigationError
from vlln.oracle.classify import AttributeTopic, OtherTopic, QuestionAnalysis
from vlln.oracle.knowledge import (
    EpisodeKnowledge,
    choose,
    material_adjective,
    object_phrase,
    room_name,
)
from vlln.oracle.route import CANNOT_ANSWER
from vlln.sim.agent import Action, AgentState
from vlln.sim.renderer import Frame
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.frame import wrap_angle, yaw_of
from vlln.world.materials import MATERIAL_TEXTURE
from vlln.world.model import ObjectInstance, Room

DONT_KNOW = "I don't know."
CLOSE_RADIUS = 3.0  # m of walking distance that count as "close" (the OS radius)
VISIBLE_MIN_SHARE = 0.0002  # of the image's pixels showing the target: "it is in your view"

_MATERIAL_NOUN = {"tile": "tiles"}
_SIZE_WORDS = {"small": "small", "tiny": "small", "little": "small", "medium": "medium"}
_SIZE_WORDS |= {"large": "large", "big": "large", "huge": "large"}
_SHAPE_WORDS = ("round", "square", "rectangular", "oval", "circular", "l-shaped", "tall", "low")
_RELATION_ORDER = ("on", "next to", "under", "above", "near")
_ASKED_RELATION = (
    (r"\b(on top of|over|above)\b", "above"),
    (r"\b(under|underneath|below|beneath)\b", "under"),
    (r"\b(on|sitting on|standing on|resting on|lying on)\b", "on"),
    (r"\b(next to|beside|besides|by)\b", "next to"),
)


def answer_attribute(
    knowledge: EpisodeKnowledge, analysis: QuestionAnalysis, state: AgentState
) -> str:
    """The asked fact about the target, or :data:`DONT_KNOW`."""
    topic = analysis.attribute or AttributeTopic.DESCRIPTION
    target = knowledge.target
    attrs = target.attributes
    rng = knowledge.rng
    # Values named in a yes/no question, which the answer confirms or corrects.
    words = analysis.text.split() if analysis.yes_no else []
    colors = analysis.colors if analysis.yes_no else ()
    materials = analysis.materials if analysis.yes_no else ()
    if topic == AttributeTopic.COLOR:
        return _checked(rng, attrs.color, colors, _color_sentence(rng, target))
    if topic == AttributeTopic.MATERIAL:
        return _checked(rng, attrs.material, materials, _material_sentence(target))
    if topic == AttributeTopic.TEXTURE:
        textures = tuple(sorted(w for w in set(MATERIAL_TEXTURE.values()) if w in words))
        return _checked(rng, attrs.texture, textures, f"It has a {attrs.texture} texture.")
    if topic == AttributeTopic.SHAPE:
        shapes = tuple(w for w in _SHAPE_WORDS if w in words)
        return _checked(rng, attrs.shape, shapes, _shape_sentence(target))
    if topic == AttributeTopic.SIZE:
        sizes = tuple(dict.fromkeys(_SIZE_WORDS[w] for w in words if w in _SIZE_WORDS))
        return _checked(rng, attrs.size, sizes, _size_sentence(target), always=True)
    if topic == AttributeTopic.ROOM:
        return _room_answer(knowledge, analysis, state)
    if topic == AttributeTopic.LOCATION:
        return _location_answer(knowledge, state)
    if topic in (AttributeTopic.NEARBY, AttributeTopic.SUPPORT):
        return _relation_answer(knowledge, analysis, topic)
    if topic == AttributeTopic.CATEGORY:
        return f"It is {with_article(target.fine_category or target.category)}."
    return _description(knowledge, state)


def _checked(
    rng: np.random.Generator,
    value: str,
    asked: tuple[str, ...],
    sentence: str,
    always: bool = False,
) -> str:
    """``sentence``, prefixed "Yes, " or "No, " when a yes/no question named one value.

    An unknown value gives :data:`DONT_KNOW` unless ``always`` (the sentence still has facts).
    """
    if not value and not always:
        return DONT_KNOW
    if len(asked) != 1 or not value:
        return sentence
    agrees = asked[0] == value or value.endswith(f" {asked[0]}")
    prefix = choose(rng, ("Yes", "Yes, indeed") if agrees else ("No", "No, actually"))
    return f"{prefix}, {sentence[0].lower()}{sentence[1:]}"


def _color_sentence(rng: np.random.Generator, target: ObjectInstance) -> str:
    color = target.attributes.color
    return choose(
        rng, (f"It is {color}.", f"Its color is {color}.", f"The {target.category} is {color}.")
    )


def _material_sentence(target: ObjectInstance) -> str:
    material = target.attributes.material
    noun = _MATERIAL_NOUN.get(material, material)
    if material == "plain":
        return "It has a plain painted finish."
    if material == "foliage":
        return "It is a living plant with leaves."
    return f"It is made of {noun}."


def _shape_sentence(target: ObjectInstance) -> str:
    shape = target.attributes.shape
    fine = target.fine_category or target.category
    if shape.lower() in _SHAPE_WORDS or shape.endswith("-shaped"):
        return f"It is {shape}."
    if shape in fine.split():
        return f"It is {with_article(fine)}."
    return f"It is {with_article(shape)} {target.category}."


def _size_sentence(target: ObjectInstance) -> str:
    sx, sy, sz = target.box.size
    dims = f"about {max(sx, sz):.1f} m wide and {sy:.1f} m tall"
    size = target.attributes.size
    if not size:
        return f"It is {dims}."
    return f"It is {size} for {with_article(target.category)}, {dims}."


# --- rooms and places ------------------------------------------------------------------------


def room_phrase(
    knowledge: EpisodeKnowledge, room: Room, state: AgentState, *, short: bool = False
) -> str:
    """How to name the room to the agent: "the kitchen"; "this bedroom, the one you are in"
    (``short``: "this bedroom") when it stands in it; "the bedroom to your left" when the
    house has several bedrooms."""
    x, y, z = state.position
    here = knowledge.index.room_at(x, z, y)
    name = room_name(room)
    if here is not None and here.id == room.id:
        return f"this {name}" if short else f"this {name}, the one you are in"
    if knowledge.index.same_type_rooms(room) == 1:
        return f"the {name}"
    polygon = np.asarray(room.polygon)
    cx, cz = polygon.mean(axis=0)
    angle = math.degrees(wrap_angle(yaw_of(float(cx) - x, float(cz) - z) - state.yaw))
    return f"the {name} {direction_words(angle)}"


def direction_words(angle: float) -> str:
    """Where a thing at ``angle`` degrees from the heading (left positive) lies: "behind you"."""
    if abs(angle) <= 45.0:
        return "ahead of you"
    if abs(angle) >= 135.0:
        return "behind you"
    return "to your left" if angle > 0 else "to your right"


def _room_answer(knowledge: EpisodeKnowledge, analysis: QuestionAnalysis, state: AgentState) -> str:
    room = knowledge.target_room
    if room is None:
        return DONT_KNOW
    sentence = f"It is in {room_phrase(knowledge, room, state)}."
    if analysis.this_room:
        x, y, z = state.position
        here = knowledge.index.room_at(x, z, y)
        return ("Yes, " if here is not None and here.id == room.id else "No, ") + sentence.lower()
    if len(analysis.rooms) == 1:
        asked = analysis.rooms[0]
        return ("Yes, " if asked == room.type else "No, ") + sentence[0].lower() + sentence[1:]
    return sentence


def _location_answer(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    room = knowledge.target_room
    parts = [f"It is in {room_phrase(knowledge, room, state, short=True)}" if room else "It is"]
    placement = knowledge.target.attributes.placement
    if placement:
        parts.append(placement)
    own = knowledge.index.relations.get(knowledge.target.id, [])
    if own:
        relation = min(own, key=lambda r: (_RELATION_ORDER.index(r.word), r.distance))
        parts.append(f"{relation.word} {object_phrase(knowledge.index.instances[relation.object])}")
    if len(parts) == 1:
        return DONT_KNOW
    return ", ".join(parts) + "."


def _relation_answer(
    knowledge: EpisodeKnowledge, analysis: QuestionAnalysis, topic: AttributeTopic
) -> str:
    """Objects related to the target: "It is next to the white sofa." or "The cup is on it.".

    The relation word comes from the question ("under it", "next to"); "what is on it?" asks
    for objects related to the target, "what is it on?" for the target's own relations.
    """
    text = analysis.text
    word = next((w for pattern, w in _ASKED_RELATION if re.search(pattern, text)), None)
    if word is None and topic == AttributeTopic.SUPPORT:
        word = "on"
    index = knowledge.index
    target_id = knowledge.target.id
    own = sorted(
        index.relations.get(target_id, []),
        key=lambda r: (_RELATION_ORDER.index(r.word), r.distance),
    )
    if _TARGET_AS_OBJECT.search(text) and word is not None:
        others = [r for r in index.relations_to.get(target_id, []) if r.word == word]
        if others:
            names = [object_phrase(index.instances[r.subject]) for r in others[:2]]
            verb = "are" if len(names) > 1 else "is"
            return f"{' and '.join(names).capitalize()} {verb} {word} it."
    asked = [r for r in own if word is None or r.word == word]
    if not asked and word == "on":
        placement = knowledge.target.attributes.placement
        sentence = f"It is {placement}." if placement else DONT_KNOW
    else:
        chosen = asked or own
        if not chosen:
            return "There is nothing right next to it."
        parts = [f"{r.word} {object_phrase(index.instances[r.object])}" for r in chosen[:2]]
        sentence = "It is " + " and ".join(parts) + "."
    if not analysis.yes_no:
        return sentence
    named = {canonical_category(m.group(1)) for m in index.category_pattern.finditer(text)}
    for relation in own:
        other = index.instances[relation.object]
        if other.category in named and (word is None or relation.word == word):
            return f"Yes, it is {relation.word} {object_phrase(other)}."
    return f"No, {sentence[0].lower()}{sentence[1:]}" if named else sentence


_TARGET_AS_OBJECT = re.compile(
    r"\b(on|under|above|below|over|underneath|on top of) (it|the (target|goal))\b"
)


def _description(knowledge: EpisodeKnowledge, state: AgentState) -> str:
    """Colour, material, size and fine category, and the room: "It is a small red wooden
    dining chair in the kitchen."."""
    target = knowledge.target
    attrs = target.attributes
    material = material_adjective(attrs.material)
    noun = target.fine_category or target.category
    words = [w for w in (attrs.size, attrs.color, material) if w and w not in noun.split()]
    phrase = with_article(" ".join([*words, noun]))
    room = knowledge.target_room
    where = f" in {room_phrase(knowledge, room, state, short=True)}" if room is not None else ""
    return choose(
        knowledge.rng,
        (f"It is {phrase}{where}.", f"You are looking for {phrase}{where}."),
    )


def with_article(phrase: str) -> str:
    """ "an armchair", "a bed"."""
    return ("an " if phrase[:1].lower() in "aeiou" else "a ") + phrase


def joined(items: list[str]) -> str:
    """ "a", "a and b", "a, b and c"."""
    return items[0] if len(items) == 1 else f"{', '.join(items[:-1])} and {items[-1]}"


# --- other -----------------------------------------------------------------------------------


def answer_other(
    knowledge: EpisodeKnowledge, analysis: QuestionAnalysis, state: AgentState, frame: Frame
) -> str:
    """The agent's room, the distance, progress or visibility; else :data:`CANNOT_ANSWER`."""
    x, y, z = state.position
    topic = analysis.other
    rng = knowledge.rng
    if topic == OtherTopic.AGENT_ROOM:
        here = knowledge.index.room_at(x, z, y)
        if here is None:
            return CANNOT_ANSWER
        if len(analysis.rooms) == 1:
            agrees = analysis.rooms[0] == here.type
            return f"{'Yes' if agrees else 'No'}, you are in the {room_name(here)}."
        return f"You are in the {room_name(here)}."
    if topic == OtherTopic.VISIBILITY:
        return _visibility(knowledge, frame)
    if topic not in (OtherTopic.DISTANCE, OtherTopic.PROGRESS):
        return CANNOT_ANSWER
    distance = knowledge.geodesic(x, z, y)
    if distance == math.inf:
        return CANNOT_ANSWER
    if distance < knowledge.follower.goal_radius:
        return choose(rng, ("You are there.", "You have arrived; it is right here."))
    away = distance_words(distance)
    if topic == OtherTopic.DISTANCE:
        if re.search(r"\bsteps?\b", analysis.text):
            steps = math.ceil(distance / knowledge.follower.motion.forward_step)
            return f"It is {away} away, about {steps} steps forward."
        return choose(
            rng, (f"It is {away} away.", f"The {knowledge.target.category} is {away} away.")
        )
    if re.search(r"\b(right|correct|wrong) (way|direction|track)\b|\bheading\b", analysis.text):
        return _heading_check(knowledge, state, away)
    if distance <= CLOSE_RADIUS:
        return choose(
            rng, (f"Yes, you are close; it is {away} away.", f"You are close, {away} to go.")
        )
    return choose(
        rng,
        (f"You are still far; it is {away} away.", f"Not yet, you are still far: {away} to go."),
    )


def distance_words(distance: float) -> str:
    """Metres as said: "less than a meter", "about 3 meters"."""
    if distance < 1.0:
        return "less than a meter"
    whole = round(distance)
    return f"about {whole} meter" + ("s" if whole > 1 else "")


def _heading_check(knowledge: EpisodeKnowledge, state: AgentState, away: str) -> str:
    """Answers "am I going the right way?": yes when the follower would go forward."""
    try:
        action = knowledge.follower.next_action(state)
    except NavigationError:
        return CANNOT_ANSWER
    if action == Action.MOVE_FORWARD:
        return f"Yes, keep going; it is {away} away."
    if action == Action.STOP:
        return "You are there."
    side = "left" if action == Action.TURN_LEFT else "right"
    return f"Not quite: turn {side}; it is {away} away."


def _visibility(knowledge: EpisodeKnowledge, frame: Frame) -> str:
    """Whether the target is in the current view, and in which part of it."""
    columns = np.nonzero(frame.instance_ids == knowledge.target.id)[1]
    if len(columns) == 0 or len(columns) < VISIBLE_MIN_SHARE * frame.instance_ids.size:
        return "No, it is not in your view right now."
    width = frame.instance_ids.shape[1]
    centre = float(np.mean(columns)) / width
    part = "on the left of" if centre < 1 / 3 else "on the right of" if centre > 2 / 3 else "in"
    where = "the middle of your view" if part == "in" else "your view"
    return f"Yes, it is {part} {where}."
