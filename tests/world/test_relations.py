"""Tests of the spatial-relation graph."""

from __future__ import annotations

import numpy as np
import pytest

from vlln.errors import ConfigError
from vlln.world.model import Attributes, Box3, ObjectInstance, Relation
from vlln.world.relations import build_relations


def make_instance(
    instance_id: int,
    lo: tuple[float, float, float],
    hi: tuple[float, float, float],
    support_id: int | None = None,
) -> ObjectInstance:
    return ObjectInstance(
        id=instance_id,
        category=f"thing{instance_id}",
        fine_category=f"thing{instance_id}",
        attributes=Attributes(),
        caption="",
        box=Box3(lo, hi),
        room_id=1,
        support_id=support_id,
    )


def words(relations: list[Relation]) -> dict[tuple[int, int], str]:
    return {(r.subject, r.object): r.word for r in relations}


def test_cup_on_table_and_table_under_cup() -> None:
    table = make_instance(1, (0.0, 0.0, 0.0), (1.2, 0.75, 0.8))
    cup = make_instance(2, (0.5, 0.75, 0.3), (0.6, 0.87, 0.4))
    got = words(build_relations([cup, table]))
    assert got == {(2, 1): "on", (1, 2): "under"}


def test_support_id_makes_on_even_with_a_gap() -> None:
    shelf = make_instance(1, (0.0, 0.0, 0.0), (1.0, 1.0, 0.4))
    book = make_instance(2, (0.2, 0.5, 0.1), (0.3, 0.7, 0.3), support_id=1)  # inside the shelf
    got = words(build_relations([shelf, book]))
    assert got == {(2, 1): "on", (1, 2): "under"}


def test_resting_needs_floor_plan_overlap() -> None:
    table = make_instance(1, (0.0, 0.0, 0.0), (1.0, 0.75, 1.0))
    # Bottom at table height but beside the table, not over it.
    beside = make_instance(2, (1.5, 0.75, 0.0), (1.6, 0.85, 0.1))
    assert words(build_relations([table, beside]))[(2, 1)] == "near"


def test_lamp_above_table_and_table_under_lamp() -> None:
    table = make_instance(1, (0.0, 0.0, 0.0), (1.0, 0.75, 1.0))
    lamp = make_instance(2, (0.3, 1.5, 0.3), (0.7, 1.7, 0.7))
    got = words(build_relations([table, lamp]))
    assert got == {(2, 1): "above", (1, 2): "under"}


def test_next_to_needs_small_gap_and_similar_height() -> None:
    bed = make_instance(1, (0.0, 0.0, 0.0), (1.6, 0.5, 2.0))
    nightstand = make_instance(2, (1.7, 0.0, 0.0), (2.2, 0.6, 0.5))  # 0.1 m gap, same floor
    got = words(build_relations([bed, nightstand]))
    assert got == {(1, 2): "next to", (2, 1): "next to"}


def test_close_but_at_another_height_is_near() -> None:
    chair = make_instance(1, (0.0, 0.0, 0.0), (0.5, 0.9, 0.5))
    cup_on_counter = make_instance(2, (0.6, 0.9, 0.0), (0.7, 1.0, 0.1))  # 0.1 m gap, 0.9 higher
    assert words(build_relations([chair, cup_on_counter])) == {(1, 2): "near", (2, 1): "near"}


def test_gap_at_next_to_limit_is_near() -> None:
    a = make_instance(1, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    b = make_instance(2, (1.5, 0.0, 0.0), (2.0, 1.0, 1.0))  # 0.5 m gap
    assert words(build_relations([a, b]))[(1, 2)] == "near"


@pytest.mark.parametrize(("gap", "joined"), [(0.99, True), (1.0, True), (1.01, False)])
def test_distance_cut_off(gap: float, joined: bool) -> None:
    a = make_instance(1, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    b = make_instance(2, (1.0 + gap, 0.0, 0.0), (2.0 + gap, 1.0, 1.0))
    relations = build_relations([a, b])
    assert (len(relations) == 2) is joined
    for relation in relations:
        assert relation.distance == pytest.approx(gap)


def test_diagonal_distance_is_euclidean() -> None:
    a = make_instance(1, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    b = make_instance(2, (1.6, 0.0, 1.6), (2.0, 1.0, 2.0))  # 0.6 m along x and z: 0.85 m
    relations = build_relations([a, b])
    assert relations[0].distance == pytest.approx(0.6 * 2**0.5)
    assert build_relations([a, b], max_distance=0.8) == []


def test_matches_box_distance_and_is_sorted_for_a_random_room() -> None:
    rng = np.random.default_rng(7)
    instances = []
    for instance_id in rng.permutation(np.arange(1, 61)):
        lo = rng.uniform(0.0, 6.0, size=3)
        hi = lo + rng.uniform(0.1, 1.0, size=3)
        instances.append(
            make_instance(
                int(instance_id),
                (float(lo[0]), float(lo[1]), float(lo[2])),
                (float(hi[0]), float(hi[1]), float(hi[2])),
            )
        )
    relations = build_relations(instances)
    keys = [(r.subject, r.object) for r in relations]
    assert keys == sorted(keys)
    by_id = {inst.id: inst for inst in instances}
    expected = {
        (a.id, b.id)
        for a in instances
        for b in instances
        if a.id != b.id and a.box.distance_to(b.box) <= 1.0
    }
    assert set(keys) == expected
    for r in relations:
        assert r.distance == pytest.approx(by_id[r.subject].box.distance_to(by_id[r.object].box))
    # Every relation has its inverse.
    inverse = {"on": "under", "above": "under", "next to": "next to", "near": "near"}
    got = words(relations)
    for (s, o), word in got.items():
        if word in inverse:
            assert got[(o, s)] == inverse[word]
        else:
            assert got[(o, s)] in ("on", "above")


def test_same_input_in_any_order_gives_the_same_graph() -> None:
    table = make_instance(3, (0.0, 0.0, 0.0), (1.2, 0.75, 0.8))
    cup = make_instance(1, (0.5, 0.75, 0.3), (0.6, 0.87, 0.4))
    chair = make_instance(2, (1.3, 0.0, 0.0), (1.8, 0.9, 0.5))
    assert build_relations([table, cup, chair]) == build_relations([chair, cup, table])


def test_too_few_instances_give_no_relations() -> None:
    assert build_relations([]) == []
    assert build_relations([make_instance(1, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))]) == []


def test_rejects_repeated_ids_and_negative_distance() -> None:
    a = make_instance(4, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    with pytest.raises(ConfigError, match=r"repeated: \[4\]"):
        build_relations([a, a])
    with pytest.raises(ConfigError, match="max_distance"):
        build_relations([a], max_distance=-1.0)


def test_plan_distance_is_the_gap_to_the_footprint_whatever_the_height() -> None:
    box = Box3((0.0, 0.5, 0.0), (2.0, 1.0, 1.0))
    assert box.plan_distance(1.0, 0.5) == 0.0  # inside the footprint
    assert box.plan_distance(5.0, 0.5) == 3.0
    assert box.plan_distance(5.0, 5.0) == 5.0  # 3 and 4 from the corner
