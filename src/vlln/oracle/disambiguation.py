"""Disambiguation answers: is the object the agent is looking at the target?

The paper's rule is "yes if the target is centred in the current view and within 3 m". Here
both parts are made exact, on the instance-id image of the asker's current frame:

* The *centre* is rows H/4..3H/4 and columns W/4..3W/4, the region the reference's data
  collection uses for "a label near the image centre".
* The target is *centred* when (1) at least :data:`CENTRE_MIN_SHARE` of the centre's pixels
  show it (192 pixels at 640x480, about a mug at 2 m), (2) no other instance of its category
  has more pixels in the centre (the asker means the most visible one), and (3) it is the
  dominant object of the centre (most pixels of any object) or at least
  :data:`CENTRED_FRACTION` of its visible pixels lie in the centre. Clause (3) accepts a
  small object on big furniture that fills the view, and rejects a target cut by the
  region's edge while something else fills the middle.
* *Within 3 m* is the floor-plan distance from the agent to the target's box.

"Yes" needs both. Otherwise "No". With cues (``cues=True``, an extension of ours), when the
most visible instance of the target's category in the centre is another one, the "No" says
how the target differs from it ("No, the one I mean is red."), and when the target itself is
centred but too far, it says how far, so that the agent walks closer instead of turning away.
Without cues the answer is yes or no alone, as the paper's oracle answers (docs/evaluation.md,
Ablations). Both draw the same paraphrases in the same order, so the other answers of an
episode are worded alike whichever is chosen.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from vlln.oracle.knowledge import EpisodeKnowledge, choose, object_phrase, room_name
from vlln.sim.agent import AgentState
from vlln.sim.renderer import Frame
from vlln.world.model import ObjectInstance

CENTRE_MIN_SHARE = 0.0025  # of the centre's pixels
CENTRED_FRACTION = 0.5  # of the target's visible pixels that lie in the centre
DISAMBIGUATION_RANGE = 3.0  # m


def centre_counts(instance_ids: np.ndarray) -> dict[int, int]:
    """Pixels per object id (ids >= 1) in the central region of an instance-id image."""
    h, w = instance_ids.shape
    centre = instance_ids[h // 4 : 3 * h // 4, w // 4 : 3 * w // 4]
    ids, counts = np.unique(centre[centre > 0], return_counts=True)
    return dict(zip(ids.tolist(), counts.tolist(), strict=True))


PLAIN_NO = ("No.", "No, that is not the one.", "No, it is not this one.")


def answer_disambiguation(
    knowledge: EpisodeKnowledge, state: AgentState, frame: Frame, cues: bool = True
) -> str:
    """Yes or no to "is this the one?"; with ``cues`` a no says why (module doc)."""
    target = knowledge.target
    index = knowledge.index
    rng = knowledge.rng
    ids = frame.instance_ids
    counts = centre_counts(ids)
    categories = {i: index.instances[i].category for i in counts if i in index.instances}
    candidate = most_visible_of(counts, ids.shape, categories, target.category)
    if candidate == target.id and is_centred(counts, target.id, ids):
        x, _, z = state.position
        distance = knowledge.plan_distance(x, z)
        if distance <= DISAMBIGUATION_RANGE:
            return choose(rng, ("Yes.", "Yes, that is the one.", "Yes, this is it."))
        if not cues:
            return "No."
        return f"No, not from here: you are still about {round(distance)} meters from it."
    if cues and candidate is not None and candidate != target.id:
        predicate = distinguishing_predicate(knowledge, index.instances[candidate])
        if predicate is not None:
            return choose(
                rng,
                (f"No, the one I mean {predicate}.", f"No. The one I am thinking of {predicate}."),
            )
    return choose(rng, PLAIN_NO)


def most_visible_of(
    counts: dict[int, int], shape: tuple[int, ...], categories: Mapping[int, str], category: str
) -> int | None:
    """The instance of ``category`` with most pixels in the centre (at least
    :data:`CENTRE_MIN_SHARE` of it), the one an asker looking there means; None if none."""
    h, w = shape[0], shape[1]
    minimum = CENTRE_MIN_SHARE * (3 * h // 4 - h // 4) * (3 * w // 4 - w // 4)
    same = [(n, i) for i, n in counts.items() if n >= minimum and categories.get(i) == category]
    return max(same)[1] if same else None


def is_centred(counts: dict[int, int], target_id: int, ids: np.ndarray) -> bool:
    if max(counts, key=lambda i: (counts[i], -i)) == target_id:
        return True
    visible = int(np.count_nonzero(ids == target_id))
    return counts[target_id] >= CENTRED_FRACTION * visible


def distinguishing_predicate(knowledge: EpisodeKnowledge, other: ObjectInstance) -> str | None:
    """How the target differs from ``other``: "is red", "is made of wood", "is in the kitchen",
    "is next to the white sofa"; None when nothing recorded tells them apart."""
    target = knowledge.target
    mine, theirs = target.attributes, other.attributes
    if mine.color and mine.color != theirs.color:
        return f"is {mine.color}"
    if mine.material not in ("", "plain") and mine.material != theirs.material:
        return f"is made of {mine.material}"
    if target.fine_category and target.fine_category != other.fine_category:
        article = "an" if target.fine_category[0] in "aeiou" else "a"
        return f"is {article} {target.fine_category}"
    if mine.size and mine.size != theirs.size:
        return f"is the {mine.size} one"
    room = knowledge.target_room
    if room is not None and target.room_id != other.room_id:
        if any(r.id == other.room_id and r.type == room.type for r in knowledge.index.house.rooms):
            return f"is in another {room_name(room)}"
        return f"is in the {room_name(room)}"
    if mine.placement and mine.placement != theirs.placement:
        return f"is {mine.placement}"
    instances = knowledge.index.instances
    theirs_near = {
        (r.word, instances[r.object].category) for r in knowledge.index.relations.get(other.id, [])
    }
    for relation in knowledge.index.relations.get(target.id, []):
        neighbour = instances[relation.object]
        if (relation.word, neighbour.category) not in theirs_near:
            return f"is {relation.word} {object_phrase(neighbour)}"
    return None
