"""Tests of the IIGN and IGN instructions and the uniqueness checker behind them."""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vlln.errors import ConfigError
from vlln.tasks.instructions import (
    FINE_CATEGORY,
    NEARBY_OBJECTS,
    ROOM,
    AmbiguousTargetError,
    AttributeConstraint,
    Constraint,
    Description,
    FullInstruction,
    InstructionWriter,
    RelationConstraint,
    RoomConstraint,
    full_instruction,
    matches,
    matching_instances,
    partial_instruction,
)
from vlln.world.model import Attributes, Box3, House, ObjectInstance, Relation, Room

ATTRIBUTE_NAMES = ("color", "material", "texture", "shape", "size")
SQUARE = ((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0))


def room(room_id: int, kind: str) -> Room:
    return Room(room_id, kind, SQUARE)


def thing(
    instance_id: int, category: str, room_id: int, fine: str = "", **words: str
) -> ObjectInstance:
    return ObjectInstance(
        id=instance_id,
        category=category,
        fine_category=fine,
        attributes=Attributes(**words),
        caption="",
        box=Box3((0.0, 0.0, 0.0), (0.5, 0.5, 0.5)),
        room_id=room_id,
    )


def both_ways(a: int, word: str, b: int) -> list[Relation]:
    inverse = {"on": "under", "under": "on"}.get(word, word)
    return [Relation(a, word, b, 0.2), Relation(b, inverse, a, 0.2)]


def make_house(instances: list[ObjectInstance], relations: list[Relation] | None = None) -> House:
    rooms = [room(1, "kitchen"), room(2, "living room"), room(3, "bedroom"), room(4, "other")]
    return House("test_house", rooms, [], instances, relations or [])


def furnished_house() -> House:
    """Chairs that differ in colour, material, room, fine category and neighbours."""
    instances = [
        thing(1, "chair", 1, color="red", material="wood", size="small"),
        thing(2, "chair", 1, color="white", material="wood", size="large"),
        thing(3, "chair", 2, color="white", material="metal", size="large"),
        thing(4, "chair", 2, color="white", material="metal", size="small"),
        thing(5, "chair", 3, "office chair", color="white", material="metal", size="small"),
        thing(6, "chair", 3, "dining chair", color="white", material="metal", size="small"),
        thing(7, "chair", 2, color="white", material="metal", size="small"),
        thing(10, "sofa", 2, color="gray", material="fabric"),
        thing(11, "sofa", 2, color="beige", material="fabric"),
        thing(12, "table", 1, color="white", material="wood"),
        thing(13, "lamp", 3, color="black", material="metal"),
    ]
    relations = [
        *both_ways(4, "next to", 10),
        *both_ways(7, "next to", 11),
        *both_ways(1, "next to", 12),
        *both_ways(2, "next to", 12),
        *both_ways(13, "on", 12),
        *both_ways(5, "near", 13),
    ]
    return make_house(instances, relations)


def candidate_constraints(house: House, inst: ObjectInstance) -> list[Constraint]:
    """Everything a full instruction may say about ``inst``, derived here independently."""
    found: set[Constraint] = set()
    for name in ATTRIBUTE_NAMES:
        if value := getattr(inst.attributes, name):
            found.add(AttributeConstraint(name, value))
    if inst.fine_category and inst.fine_category != inst.category:
        found.add(AttributeConstraint(FINE_CATEGORY, inst.fine_category))
    kinds = {r.id: r.type for r in house.rooms}
    if kinds.get(inst.room_id, "") not in ("", "other"):
        found.add(RoomConstraint(kinds[inst.room_id]))
    for rel in house.relations:
        if rel.subject != inst.id:
            continue
        other = house.instance(rel.object)
        found.add(RelationConstraint(rel.word, other.category))
        for name in ATTRIBUTE_NAMES:
            if value := getattr(other.attributes, name):
                found.add(
                    RelationConstraint(rel.word, other.category, AttributeConstraint(name, value))
                )
    return sorted(found, key=repr)


def phrases(constraint: Constraint) -> list[str]:
    """Words the sentence must contain for ``constraint`` to count as stated."""
    if isinstance(constraint, AttributeConstraint):
        return [constraint.value]
    if isinstance(constraint, RoomConstraint):
        return [constraint.room_type]
    extra = [constraint.attribute.value] if constraint.attribute else []
    return [constraint.word, constraint.category, *extra]


def info_name(constraint: Constraint) -> str:
    if isinstance(constraint, AttributeConstraint):
        return constraint.name
    return ROOM if isinstance(constraint, RoomConstraint) else NEARBY_OBJECTS


def check_instruction(house: House, target_id: int, result: FullInstruction) -> None:
    """The description singles out the target, is minimal, and the text says exactly it."""
    description = result.description
    assert matching_instances(house, description) == [target_id]
    target = house.instance(target_id)
    candidates = candidate_constraints(house, target)
    for size in range(len(description.constraints)):
        for combo in itertools.combinations(candidates, size):
            shorter = Description(target.category, combo)
            assert matching_instances(house, shorter) != [target_id], combo
    text = result.text
    assert text[0].isupper() and text.endswith(".") and "  " not in text
    for constraint in description.constraints:
        for phrase in phrases(constraint):
            assert phrase in text, (phrase, text)
    stated = [info_name(c) for c in description.constraints]
    assert sorted(result.instruction_info) == sorted(set(stated))
    assert len(set(result.instruction_info)) == len(result.instruction_info)
    said = {phrase for c in description.constraints for phrase in phrases(c)}
    for name in ATTRIBUTE_NAMES:
        value = getattr(target.attributes, name)
        if name not in result.instruction_info and value and value not in said:
            assert value not in text.split(), (name, text)


# --- partial instructions ---------------------------------------------------------------


def test_partial_instruction_names_only_the_category() -> None:
    assert partial_instruction("chair") == "Search for the chair."
    assert partial_instruction("coffee table") == "Search for the coffee table."


@pytest.mark.parametrize("category", ["", " chair", "chair "])
def test_partial_instruction_rejects_malformed_categories(category: str) -> None:
    with pytest.raises(ConfigError):
        partial_instruction(category)


# --- the uniqueness checker -------------------------------------------------------------


def test_matching_checks_category_attributes_room_and_relations() -> None:
    house = furnished_house()
    white = AttributeConstraint("color", "white")
    assert matching_instances(house, Description("chair")) == [1, 2, 3, 4, 5, 6, 7]
    assert matching_instances(house, Description("chair", (white,))) == [2, 3, 4, 5, 6, 7]
    in_living = RoomConstraint("living room")
    assert matching_instances(house, Description("chair", (white, in_living))) == [3, 4, 7]
    by_sofa = RelationConstraint("next to", "sofa")
    assert matching_instances(house, Description("chair", (by_sofa,))) == [4, 7]
    by_gray_sofa = RelationConstraint("next to", "sofa", AttributeConstraint("color", "gray"))
    assert matching_instances(house, Description("chair", (by_gray_sofa,))) == [4]
    assert matches(house, house.instance(4), Description("chair", (by_gray_sofa,)))
    assert not matches(house, house.instance(7), Description("chair", (by_gray_sofa,)))
    assert not matches(house, house.instance(10), Description("chair"))
    near_sofa = RelationConstraint("near", "sofa")  # right category, wrong word
    assert matching_instances(house, Description("chair", (near_sofa,))) == []


def test_room_constraint_matches_every_room_of_that_type() -> None:
    rooms = [room(1, "bedroom"), room(2, "bedroom"), room(3, "kitchen")]
    instances = [thing(1, "bed", 1), thing(2, "bed", 2), thing(3, "bed", 3)]
    house = House("two_bedrooms", rooms, [], instances)
    assert matching_instances(house, Description("bed", (RoomConstraint("bedroom"),))) == [1, 2]


@pytest.mark.parametrize(
    "make",
    [
        lambda: AttributeConstraint("color", ""),
        lambda: AttributeConstraint("weight", "heavy"),
        lambda: RoomConstraint(""),
        lambda: RelationConstraint("", "table"),
        lambda: RelationConstraint("on", ""),
        lambda: Description(""),
    ],
)
def test_malformed_constraints_are_rejected(make: object) -> None:
    with pytest.raises(ConfigError):
        make()  # type: ignore[operator]


# --- full instructions ------------------------------------------------------------------


def test_unique_colour_alone_is_enough() -> None:
    house = furnished_house()
    result = full_instruction(house, 1, np.random.default_rng(0))
    assert result.description.constraints == (AttributeConstraint("color", "red"),)
    assert result.instruction_info == ["color"]
    assert "red chair" in result.text
    check_instruction(house, 1, result)


def test_every_instance_gets_a_minimal_truthful_instruction() -> None:
    house = furnished_house()
    writer = InstructionWriter(house)
    rng = np.random.default_rng(3)
    for inst in house.instances:
        check_instruction(house, inst.id, writer.full_instruction(inst.id, rng))


def test_relation_phrases_name_the_neighbour_and_its_attribute() -> None:
    house = furnished_house()
    result = full_instruction(house, 4, np.random.default_rng(0))
    # Chairs 4 and 7 differ only in the colour of the sofa they stand next to.
    expected = RelationConstraint("next to", "sofa", AttributeConstraint("color", "gray"))
    assert result.description.constraints == (expected,)
    assert "next to the gray sofa" in result.text
    assert result.instruction_info == [NEARBY_OBJECTS]


def test_fine_category_replaces_the_noun() -> None:
    house = furnished_house()
    result = full_instruction(house, 6, np.random.default_rng(0))
    assert result.description.constraints == (AttributeConstraint(FINE_CATEGORY, "dining chair"),)
    assert "dining chair" in result.text
    assert result.instruction_info == [FINE_CATEGORY]


def test_sole_instance_of_its_category_needs_no_constraint() -> None:
    house = furnished_house()
    result = full_instruction(house, 13, np.random.default_rng(0), max_constraints=0)
    assert result.description.constraints == ()
    assert result.instruction_info == []
    assert result.text.endswith("the lamp.")


@pytest.mark.parametrize(
    ("target_words", "expected"),
    [
        # Unique by colour and by room: colour is noticed first.
        ({"color": "red", "material": "wood"}, AttributeConstraint("color", "red")),
        # Unique by room and by material: the room comes before material.
        ({"color": "white", "material": "glass"}, RoomConstraint("kitchen")),
    ],
)
def test_noticeable_attributes_are_preferred(
    target_words: dict[str, str], expected: Constraint
) -> None:
    instances = [
        thing(1, "vase", 1, **target_words),
        thing(2, "vase", 2, color="white", material="wood"),
        thing(3, "vase", 3, color="white", material="wood"),
    ]
    house = make_house(instances)
    for seed in range(5):
        result = full_instruction(house, 1, np.random.default_rng(seed))
        assert result.description.constraints == (expected,)


def test_the_cheapest_of_several_shortest_descriptions_wins() -> None:
    instances = [
        thing(1, "vase", 1, color="red", material="wood", size="small"),
        thing(2, "vase", 1, color="white", material="metal", size="small"),
        thing(3, "vase", 1, color="white", material="wood", size="large"),
        thing(4, "vase", 3, color="red", material="wood", size="large"),
    ]
    house = make_house(instances)
    # Colour + room, colour + size and material + size all single out vase 1.
    expected = (AttributeConstraint("color", "red"), RoomConstraint("kitchen"))
    for seed in range(10):
        result = full_instruction(house, 1, np.random.default_rng(seed))
        assert result.description.constraints == expected
        assert result.instruction_info == ["color", ROOM]


def test_a_relation_is_preferred_over_material() -> None:
    instances = [
        thing(1, "stool", 1, color="red", material="metal"),
        thing(2, "stool", 1, color="red", material="wood"),
        thing(3, "table", 1, color="white"),
    ]
    house = make_house(instances, both_ways(1, "next to", 3))
    result = full_instruction(house, 1, np.random.default_rng(0))
    assert result.description.constraints == (RelationConstraint("next to", "table"),)


def test_equal_ties_are_broken_by_the_rng() -> None:
    instances = [
        thing(1, "plant", 1, color="green"),
        thing(2, "plant", 1, color="green"),
        thing(3, "lamp", 1, color="black"),
        thing(4, "clock", 1, color="black"),
    ]
    relations = [*both_ways(1, "near", 3), *both_ways(1, "near", 4)]
    house = make_house(instances, relations)
    chosen = {
        full_instruction(house, 1, np.random.default_rng(seed)).description.constraints
        for seed in range(30)
    }
    assert chosen == {
        (RelationConstraint("near", "lamp"),),
        (RelationConstraint("near", "clock"),),
    }


def test_neighbour_of_the_same_category_is_another_one() -> None:
    instances = [thing(1, "cup", 1, color="blue"), thing(2, "cup", 1, color="red")]
    instances.append(thing(3, "cup", 1, color="blue"))
    house = make_house(instances, both_ways(1, "next to", 2))
    result = full_instruction(house, 1, np.random.default_rng(0))
    assert "next to another" in result.text
    check_instruction(house, 1, result)


def test_identical_twins_raise_a_typed_error_naming_the_twin() -> None:
    instances = [
        thing(1, "chair", 1, color="white", material="wood"),
        thing(2, "chair", 1, color="white", material="wood"),
        thing(3, "chair", 2, color="white", material="wood"),
    ]
    house = make_house(instances)
    with pytest.raises(AmbiguousTargetError, match=r"\[2\]"):
        full_instruction(house, 1, np.random.default_rng(0))
    assert issubclass(AmbiguousTargetError, ConfigError)
    check_instruction(house, 3, full_instruction(house, 3, np.random.default_rng(0)))


def test_unknown_attributes_and_unnamed_rooms_are_never_used() -> None:
    # Chair 1 differs from 2 only by an unknown colour and by standing in an "other" room.
    instances = [
        thing(1, "chair", 4, material="wood"),
        thing(2, "chair", 1, color="red", material="wood"),
    ]
    house = make_house(instances)
    with pytest.raises(AmbiguousTargetError):
        full_instruction(house, 1, np.random.default_rng(0))
    result = full_instruction(house, 2, np.random.default_rng(0))
    assert result.instruction_info == ["color"]


def test_a_target_needing_too_many_constraints_raises() -> None:
    instances = [
        thing(1, "mug", 1, color="red", material="metal"),
        thing(2, "mug", 1, color="red", material="glass"),
        thing(3, "mug", 1, color="blue", material="metal"),
    ]
    house = make_house(instances)
    with pytest.raises(AmbiguousTargetError, match="more than 1"):
        full_instruction(house, 1, np.random.default_rng(0), max_constraints=1)
    result = full_instruction(house, 1, np.random.default_rng(0), max_constraints=2)
    assert result.instruction_info == ["color", "material"]
    check_instruction(house, 1, result)


def test_bad_arguments_raise_config_errors() -> None:
    house = furnished_house()
    with pytest.raises(ConfigError, match="no instance 99"):
        full_instruction(house, 99, np.random.default_rng(0))
    with pytest.raises(ConfigError, match="max_constraints"):
        InstructionWriter(house, max_constraints=-1)


def test_same_seed_same_text_and_the_rng_varies_the_phrasing() -> None:
    house = furnished_house()

    def texts(seed: int) -> list[str]:
        writer = InstructionWriter(house)
        rng = np.random.default_rng(seed)
        return [writer.full_instruction(inst.id, rng).text for inst in house.instances]

    assert texts(11) == texts(11)
    assert len({tuple(texts(seed)) for seed in range(6)}) > 1
    one = full_instruction(house, 3, np.random.default_rng(5))
    assert one == InstructionWriter(house).full_instruction(3, np.random.default_rng(5))


@pytest.mark.slow
def test_texts_do_not_depend_on_the_string_hash_seed() -> None:
    """Constraint sets are hashed; the choice among them must not follow set order."""
    script = (
        "import numpy as np\n"
        "from tests.tasks.test_instructions import random_house\n"
        "from vlln.tasks.instructions import InstructionWriter\n"
        "house = random_house(0, categories=3, per_category=10, neighbours=3)\n"
        "writer, rng = InstructionWriter(house), np.random.default_rng(2)\n"
        "print([writer.full_instruction(i.id, rng).text for i in house.instances])\n"
    )
    root = Path(__file__).resolve().parents[2]
    outputs = set()
    for hash_seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": hash_seed}
        run = subprocess.run(
            [sys.executable, "-c", script], cwd=root, env=env, capture_output=True, text=True
        )
        assert run.returncode == 0, run.stderr
        outputs.add(run.stdout)
    assert len(outputs) == 1


# --- random houses ----------------------------------------------------------------------


def random_house(seed: int, categories: int, per_category: int, neighbours: int) -> House:
    rng = np.random.default_rng(seed)
    colors, materials, sizes = ("red", "white", "gray"), ("wood", "metal"), ("small", "large")
    instances = [
        thing(
            1 + c * per_category + j,
            f"thing{c}",
            int(rng.integers(1, 5)),
            color=str(rng.choice(colors)),
            material=str(rng.choice(materials)),
            size=str(rng.choice(sizes)),
        )
        for c in range(categories)
        for j in range(per_category)
    ]
    words = ("near", "next to", "on")
    relations: list[Relation] = []
    for inst in instances:
        for other in rng.choice(len(instances), size=neighbours, replace=False):
            if instances[other].id != inst.id:
                word = str(rng.choice(words))
                relations.append(Relation(inst.id, word, instances[other].id, 0.5))
    return make_house(instances, relations)


@pytest.mark.parametrize("seed", range(4))
def test_random_houses_get_minimal_instructions_or_are_truly_ambiguous(seed: int) -> None:
    house = random_house(seed, categories=2, per_category=8, neighbours=1)
    writer = InstructionWriter(house, max_constraints=3)
    rng = np.random.default_rng(seed)
    for inst in house.instances:
        everything = Description(inst.category, tuple(candidate_constraints(house, inst)))
        try:
            result = writer.full_instruction(inst.id, rng)
        except AmbiguousTargetError:
            rivals = matching_instances(house, everything)
            if rivals == [inst.id]:  # unique, but only with more than 3 constraints
                for combo in itertools.combinations(everything.constraints, 3):
                    assert matching_instances(house, Description(inst.category, combo)) != [inst.id]
            continue
        check_instruction(house, inst.id, result)


def test_a_300_instance_house_gets_instructions_for_nearly_every_instance() -> None:
    house = random_house(0, categories=10, per_category=30, neighbours=6)
    writer = InstructionWriter(house)
    rng = np.random.default_rng(0)
    written = 0
    for inst in house.instances:
        try:
            writer.full_instruction(inst.id, rng)
            written += 1
        except AmbiguousTargetError:
            pass
    assert written > 250
