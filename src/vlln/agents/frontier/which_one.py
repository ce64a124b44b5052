"""Which of the candidates in view is the target: the question, and the answer read back.

With several instances of the target's category in view, "is this the one?" about one of them
can be answered only about that one. The comparing navigator (``FrontierConfig.compares``)
asks instead which one it is, and reads the helpful oracle's answers that name a place in the
view ("It is the one on the right.", "Neither: the chair I mean is not in your view.", "No.
Two chairs are in view; the one I mean is the one on the left."). An answer that names no
place it can read gives no pick, so the paper's oracle, which has no such answers, leaves the
navigator playing as the plain frontier agent does.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

COMPARISON_QUESTION = "Is it the one on the left or the one on the right?"

# Where in the view each place word puts the target, 0 at the left edge and 1 at the right.
_PLACES = {"left": 0.0, "middle": 0.5, "front": 0.5, "right": 1.0}
_PLACE = re.compile(r"\b(?:the one|it is|it's)\b[^.;:]*?\b(left|middle|front|right)\b")
_NONE = re.compile(r"^\s*(?:neither|none)\b|\b(?:neither|none) (?:is|of them is) the one\b")
_NAMES_A_PLACE = re.compile(r"^\s*(?:yes, |no, )?(?:it is|it's|only one|neither|none)\b")
_CLARIFIES = re.compile(r"\bthe one i mean is\b|\bare in view\b")


@dataclass(frozen=True)
class Pick:
    """What an answer says about the candidates in view: where the target is (0 left, 1
    right), or that none of them is it (``place`` None)."""

    place: float | None


def read_comparison(answer: str) -> Pick | None:
    """The pick in an answer to :data:`COMPARISON_QUESTION`; None when it names no place
    (a refusal, a turn instruction, "No.")."""
    text = answer.lower()
    if not _NAMES_A_PLACE.match(text):
        return None
    return _pick(text)


def read_clarification(answer: str) -> Pick | None:
    """The pick in a clarification added to "is this the one?" ("No. Two chairs are in view;
    the one I mean is the one on the left."); None without one."""
    text = answer.lower()
    if not _CLARIFIES.search(text):
        return None
    return _pick(text[text.find(".") + 1 :])


def _pick(text: str) -> Pick | None:
    if _NONE.search(text):
        return Pick(None)
    match = _PLACE.search(text)
    return Pick(_PLACES[match.group(1)]) if match else None


def take(pick: Pick, in_view: Sequence[tuple[int, float]], rejected: set[int]) -> int | None:
    """The candidate in view that ``pick`` names, the others in view added to ``rejected``
    (all of them when the pick is that none is the target)."""
    chosen = picked(pick, in_view)
    rejected.update(instance for instance, _ in in_view if instance != chosen)
    if chosen is not None:
        rejected.discard(chosen)
    return chosen


def picked(pick: Pick, columns: Sequence[tuple[int, float]]) -> int | None:
    """The instance among ``columns`` ((id, mean column 0..1), left to right) at the pick's
    place: the leftmost for "left", the rightmost for "right", the most central otherwise."""
    place = pick.place
    if place is None or not columns:
        return None
    if place == 0.0:
        return columns[0][0]
    if place == 1.0:
        return columns[-1][0]
    return min(columns, key=lambda c: abs(c[1] - place))[0]
