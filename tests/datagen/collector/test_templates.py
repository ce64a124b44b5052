"""Every question the collector can ask is typed by the oracle as the trigger means it."""

from __future__ import annotations

import numpy as np
import pytest

from vlln.datagen.collector.templates import (
    ATTRIBUTE_TEMPLATES,
    DISAMBIGUATION_TEMPLATES,
    ROUTE_TEMPLATES,
    fill,
)
from vlln.oracle.classify import classify_question
from vlln.tasks.oracle_protocol import QuestionType

CASES = [
    *((t, QuestionType.ATTRIBUTE) for ts in ATTRIBUTE_TEMPLATES.values() for t in ts),
    *((t, QuestionType.ROUTE) for t in ROUTE_TEMPLATES),
    *((t, QuestionType.DISAMBIGUATION) for t in DISAMBIGUATION_TEMPLATES),
]


@pytest.mark.parametrize("category", ["chair", "floor lamp", "tv"])
@pytest.mark.parametrize(("template", "expected"), CASES)
def test_template_is_classified_as_its_trigger(
    template: str, expected: QuestionType, category: str
) -> None:
    assert classify_question(template.format(category=category)) == expected


def test_reference_sized_paraphrase_sets() -> None:
    assert len(ROUTE_TEMPLATES) >= 12 and len(DISAMBIGUATION_TEMPLATES) >= 24
    assert all(len(set(ts)) == len(ts) >= 2 for ts in ATTRIBUTE_TEMPLATES.values())


def test_fill_is_seeded() -> None:
    a = [fill(ROUTE_TEMPLATES, "bed", np.random.default_rng(4)) for _ in range(3)]
    b = [fill(ROUTE_TEMPLATES, "bed", np.random.default_rng(4)) for _ in range(3)]
    assert a == b and all("{" not in text for text in a)
