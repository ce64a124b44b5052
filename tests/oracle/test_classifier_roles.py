"""House words are read by role, longest phrase first; other words stay as they are."""

from vlln.oracle.classifier.model import featured_by_role
from vlln.oracle.classifier.roles import COLOUR, MATERIAL, OBJECT, ROOM, with_roles


def test_phrases_of_several_words_are_one_role() -> None:
    words = ["is", "the", "coffee", "table", "light", "gray"]
    assert with_roles(words) == ["is", "the", OBJECT, COLOUR]


def test_every_vocabulary_has_its_role_and_other_words_stay() -> None:
    words = ["wooden", "sofa", "in", "the", "kitchen", "or", "garden"]
    assert with_roles(words) == [MATERIAL, OBJECT, "in", "the", ROOM, "or", "garden"]


def test_an_object_that_is_also_a_room_reads_as_the_object() -> None:
    assert with_roles(["toilet"]) == [OBJECT]


def test_plurals_read_as_objects_and_the_question_mark_stays() -> None:
    assert featured_by_role("Any CHAIRS near the bed?") == f"any {OBJECT} near the {OBJECT} zqmark"
