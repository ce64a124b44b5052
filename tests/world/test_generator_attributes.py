"""Tests of the words and captions of generated instances."""

from __future__ import annotations

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.generator.attributes import caption, describe, placement_words
from vlln.world.mesh import Mesh
from vlln.world.model import Attributes


def build_nothing(style: Style, rng: np.random.Generator) -> ObjectModel:
    return ObjectModel(Mesh.empty())


CHAIR = Category(
    name="chair",
    shapes={"straight-backed": "dining chair", "office": "office chair"},
    colors=("red",),
    materials=("wood",),
    placement=Placement.AT_TABLE,
    rooms={"dining room": 4.0},
    build=build_nothing,
)


def test_describe_reads_the_style_and_the_placement() -> None:
    style = Style("red", "wood", "straight-backed", scale=1.1)
    fine, attributes, text = describe(CHAIR, style, "at the table", "dining room")
    assert fine == "dining chair"
    assert attributes == Attributes(
        color="red",
        material="wood",
        texture="grained",
        shape="straight-backed",
        size="large",
        placement="at the table",
    )
    assert text == "A large red wooden dining chair at the table in the dining room."


def test_captions_use_an_before_vowels_and_name_corners() -> None:
    attributes = Attributes(
        color="orange", material="plain", size="small", placement="in the corner"
    )
    assert caption("armchair", attributes, "study") == (
        "A small orange armchair in a corner of the study."
    )
    attributes = Attributes(color="orange", material="plain", size="", placement="on the wall")
    assert caption("clock", attributes, "kitchen") == "An orange clock on the wall in the kitchen."


def test_placement_words_name_the_support() -> None:
    assert placement_words(Placement.ON_SURFACE, "table") == "on the table"
    assert placement_words(Placement.WALL_MOUNTED) == "on the wall"
    assert placement_words(Placement.ON_SURFACE) == "on a surface"
