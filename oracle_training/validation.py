"""An honest accuracy figure without a held-out file: cross-validation over question families.

A plain random split flatters a classifier trained on templates: "is the sofa red" in the
training folds and "is the lamp blue" in the test fold are the same question. So questions
are grouped into *families* by their skeleton, the question read in lower case with every
vocabulary value (object, room, colour and material names, typos corrected) replaced by its
kind's slot; a family is never split between training and test. Hand-written questions are mostly
families of one. A second figure trains on every set but one and tests on that one (leave one
source out), a different writer's questions.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

from sklearn.model_selection import GroupKFold

from oracle_training.training import train_artefact
from vlln.oracle.classifier.entities import (
    MATERIAL_SYNONYMS,
    ROOM_SYNONYMS,
    corrected_words,
)
from vlln.oracle.classifier.model import classifier_from_bytes, prepared
from vlln.oracle.question_set import LabelledQuestion
from vlln.oracle.topics import parse_label
from vlln.world.catalogue.aliases import aliases_of
from vlln.world.catalogue.registry import default_catalogue
from vlln.world.materials import COLORS


@cache
def _slots() -> tuple[re.Pattern[str], dict[str, str]]:
    """A pattern matching every vocabulary value, and the slot of each (a room and an object
    ask different questions: "is this the kitchen" is not "is this the sofa")."""
    names = {c.name for c in default_catalogue()}
    slot = dict.fromkeys([*names, *aliases_of(names)], "<object>")
    slot |= dict.fromkeys(COLORS, "<colour>") | dict.fromkeys(MATERIAL_SYNONYMS, "<material>")
    slot |= dict.fromkeys(ROOM_SYNONYMS, "<room>")
    ordered = sorted(slot, key=lambda v: (-len(v), v))
    pattern = re.compile(r"\b(?:" + "|".join(re.escape(v) for v in ordered) + r")\b")
    return pattern, slot


def family(question: str) -> str:
    """The question's skeleton: its words with vocabulary values replaced by their slot."""
    text = " ".join(corrected_words(prepared(question).split()))
    pattern, slot = _slots()
    return pattern.sub(lambda match: slot[match.group(0)], text)


@dataclass(frozen=True)
class Miss:
    """A question the fold's model typed wrong."""

    question: str
    source: str
    truth: str
    predicted: str


def _scored(
    train: Sequence[LabelledQuestion],
    test: Sequence[tuple[str, LabelledQuestion]],
    seed: int,
) -> tuple[int, int, list[Miss]]:
    """Right types, right labels and the type misses of a model fitted to ``train``."""
    model = classifier_from_bytes(train_artefact(train, seed))
    types = labels = 0
    misses = []
    for source, question in test:
        label = model.predict(question.question)
        labels += label == question.label
        if parse_label(label)[0] == question.question_type:
            types += 1
        else:
            misses.append(Miss(question.question, source, str(question.label), label))
    return types, labels, misses


def grouped_cv(
    sets: Mapping[str, Sequence[LabelledQuestion]], folds: int, seed: int
) -> dict[str, Any]:
    """Type and label accuracy of models fitted to ``folds`` - 1 folds of the families and
    tested on the last, over every fold; with the accuracy per source set and the misses."""
    items = [(name, q) for name, questions in sets.items() for q in questions]
    groups = [family(q.question) for _, q in items]
    types = labels = 0
    misses: list[Miss] = []
    for train_at, test_at in GroupKFold(n_splits=folds).split(items, groups=groups):
        fitted = _scored([items[i][1] for i in train_at], [items[i] for i in test_at], seed)
        types, labels = types + fitted[0], labels + fitted[1]
        misses.extend(fitted[2])
    per_source = Counter(name for name, _ in items)
    wrong = Counter(m.source for m in misses)
    return {
        "questions": len(items),
        "families": len(set(groups)),
        "folds": folds,
        "type_accuracy": types / len(items),
        "label_accuracy": labels / len(items),
        "type_accuracy_by_set": {n: 1 - wrong[n] / per_source[n] for n in per_source},
        "misses": [m.__dict__ for m in misses],
    }


def leave_one_out(
    sets: Mapping[str, Sequence[LabelledQuestion]], test_set: str, seed: int
) -> dict[str, Any]:
    """Type and label accuracy on set ``test_set`` of a model fitted to the other sets (less
    any question that reads the same as one of the test set)."""
    test = [(test_set, q) for q in sets[test_set]]
    seen = {prepared(q.question) for _, q in test}
    train = [
        q
        for name, questions in sets.items()
        if name != test_set
        for q in questions
        if prepared(q.question) not in seen
    ]
    types, labels, misses = _scored(train, test, seed)
    return {
        "test_set": test_set,
        "questions": len(test),
        "type_accuracy": types / len(test),
        "label_accuracy": labels / len(test),
        "misses": [m.__dict__ for m in misses],
    }
