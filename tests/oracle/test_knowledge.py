"""The house index finds the objects a question names, and no object in its grammar."""

import pytest

from vlln.oracle.knowledge import HouseIndex
from vlln.world.generator import generate_house


@pytest.mark.slow
def test_the_auxiliary_can_is_not_the_object_can() -> None:
    house = next(h for h in map(generate_house, range(20)) if h.instances_of("can"))
    pattern = HouseIndex.build(house).category_pattern
    named = [m.group(1) for m in pattern.finditer("can it be found next to the can?")]
    assert named == ["can"]
    question = "can you see it by the cans"
    assert [m.start() for m in pattern.finditer(question)] == [question.index("cans")]
    assert not list(pattern.finditer("can i find it there? can we go?"))
