"""Earlier names of renamed categories still find them, wherever a category is read."""

from __future__ import annotations

import pytest

from vlln.errors import UnknownCategoryError
from vlln.world.catalogue.aliases import ALIASES, canonical_category
from vlln.world.catalogue.registry import default_catalogue
from vlln.world.generator import generate_house
from vlln.world.scans import map_category


def test_every_alias_names_a_category_and_no_category_is_an_alias() -> None:
    catalogue = default_catalogue()
    for alias, name in ALIASES.items():
        assert catalogue.get(alias) is catalogue.get(name)
        assert alias not in catalogue.names
    assert catalogue.get("sofa").name == "couch"
    assert canonical_category("chair") == "chair"


def test_an_unknown_name_is_still_an_error() -> None:
    with pytest.raises(UnknownCategoryError, match="unknown object category 'sofaa'"):
        default_catalogue().get("sofaa")


def test_houses_and_scan_annotations_answer_to_the_old_names() -> None:
    house = generate_house(1)
    couches = house.instances_of("couch")
    assert couches and house.instances_of("sofa") == couches
    assert all(inst.category == "couch" for inst in couches)
    assert map_category("trash can") == ("garbage", True)
    assert map_category("Radiator") == ("heater", True)
