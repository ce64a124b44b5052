"""The spatial-relation graph: Sr3D-style words joining instances that are close to each other.

The oracle and the instruction writer single out an instance by its neighbours ("the cup on
the table", "the chair next to the bed"), so every pair of instances whose 3-D boxes are
within ``max_distance`` (1 m, as in the released data) is joined, in both directions, by one
word chosen by the first rule that holds for ``subject <word> object``:

1. ``"on"``: the subject rests on the object: its ``support_id`` is the object, or the boxes
   overlap in the floor plan and the subject's bottom is within :data:`RESTING_TOLERANCE` of
   the object's top. ``"under"`` is the same rule with the two swapped.
2. ``"above"``: the boxes overlap in the floor plan and the subject is entirely higher than the
   object without resting on it (a lamp over a table, a picture over a sofa). The inverse is
   ``"under"``, since the word list has no separate "below".
3. ``"next to"``: the gap between the boxes is below :data:`NEXT_TO_MAX_GAP` and their bottoms
   are within :data:`SIMILAR_HEIGHT_TOLERANCE` of each other (two chairs, a bed and its
   nightstand), so a cup on a table is not "next to" the chair beside the table.
4. ``"near"``: any other pair within ``max_distance``.

"next to" and "near" are symmetric and the other words come in inverse pairs, so both
directions of every pair are recorded and the graph can be read from either end.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from vlln.errors import ConfigError
from vlln.world.model import ObjectInstance, Relation

RESTING_TOLERANCE = 0.05  # m; |subject bottom - object top| for "on"
NEXT_TO_MAX_GAP = 0.3  # m; box gap below which a pair of similar height is "next to"
SIMILAR_HEIGHT_TOLERANCE = 0.3  # m; bottoms this close stand at a "similar height"
RELATION_WORDS: tuple[str, ...] = ("on", "under", "above", "next to", "near")

_ON, _UNDER, _ABOVE, _NEXT_TO, _NEAR = range(len(RELATION_WORDS))


def build_relations(
    instances: Sequence[ObjectInstance], max_distance: float = 1.0
) -> list[Relation]:
    """All relations between instances whose boxes are at most ``max_distance`` metres apart.

    The result is sorted by subject id, then object id, and holds both directions of each
    pair. Raises :class:`ConfigError` for a negative distance or repeated instance ids.
    """
    if not max_distance >= 0.0:
        raise ConfigError(f"max_distance must be a distance >= 0 m, got {max_distance!r}")
    ordered = sorted(instances, key=lambda inst: inst.id)
    ids = np.array([inst.id for inst in ordered], dtype=np.int64)
    if len(np.unique(ids)) != len(ids):
        repeated = sorted({int(i) for i in ids if np.count_nonzero(ids == i) > 1})
        raise ConfigError(f"instance ids must be unique; repeated: {repeated}")
    if len(ordered) < 2:
        return []

    lo = np.array([inst.box.min for inst in ordered], dtype=np.float64)  # (n, 3)
    hi = np.array([inst.box.max for inst in ordered], dtype=np.float64)
    # gap[s, o, axis]: how far apart the two boxes are along one axis (0 when they overlap).
    gap = np.maximum(0.0, np.maximum(lo[None, :, :] - hi[:, None, :], lo[:, None, :] - hi[None]))
    distance = np.sqrt(np.sum(gap * gap, axis=2))
    close = distance <= max_distance
    np.fill_diagonal(close, False)
    subjects, objects = np.nonzero(close)  # row-major: sorted by subject id, then object id
    if len(subjects) == 0:
        return []

    words = _classify(ordered, lo, hi, distance, subjects, objects)
    return [
        Relation(
            subject=int(ids[s]),
            word=RELATION_WORDS[w],
            object=int(ids[o]),
            distance=float(distance[s, o]),
        )
        for s, o, w in zip(subjects, objects, words, strict=True)
    ]


def _classify(
    ordered: Sequence[ObjectInstance],
    lo: NDArray[np.float64],
    hi: NDArray[np.float64],
    distance: NDArray[np.float64],
    subjects: NDArray[np.intp],
    objects: NDArray[np.intp],
) -> NDArray[np.intp]:
    """The word index of each ``(subject, object)`` pair, by the rules of the module doc."""
    s_lo, s_hi, o_lo, o_hi = lo[subjects], hi[subjects], lo[objects], hi[objects]
    plan_overlap = np.all(
        (s_lo[:, [0, 2]] < o_hi[:, [0, 2]]) & (o_lo[:, [0, 2]] < s_hi[:, [0, 2]]), axis=1
    )
    support = np.array(
        [-1 if inst.support_id is None else inst.support_id for inst in ordered], dtype=np.int64
    )
    ids = np.array([inst.id for inst in ordered], dtype=np.int64)
    s_on_o = (support[subjects] == ids[objects]) | (
        plan_overlap & (np.abs(s_lo[:, 1] - o_hi[:, 1]) <= RESTING_TOLERANCE)
    )
    o_on_s = (support[objects] == ids[subjects]) | (
        plan_overlap & (np.abs(o_lo[:, 1] - s_hi[:, 1]) <= RESTING_TOLERANCE)
    )
    s_above_o = plan_overlap & (s_lo[:, 1] > o_hi[:, 1])
    o_above_s = plan_overlap & (o_lo[:, 1] > s_hi[:, 1])
    next_to = (distance[subjects, objects] < NEXT_TO_MAX_GAP) & (
        np.abs(s_lo[:, 1] - o_lo[:, 1]) <= SIMILAR_HEIGHT_TOLERANCE
    )
    return np.select(
        [s_on_o, o_on_s, s_above_o, o_above_s, next_to],
        [_ON, _UNDER, _ABOVE, _UNDER, _NEXT_TO],
        default=_NEAR,
    ).astype(np.intp)
