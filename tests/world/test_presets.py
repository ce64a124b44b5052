"""House presets: the small houses stay as they were; mp3d houses are drawn from the seed."""

from __future__ import annotations

import pytest

from vlln.errors import ConfigError, HouseParametersError
from vlln.tasks.scenes import (
    canonical_seed,
    house_scene_id,
    is_procedural,
    procedural_house,
    procedural_preset,
    procedural_scene_id,
)
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.generator.presets import MP3D, generate_preset_house, preset


def test_the_small_preset_is_the_default_house_byte_for_byte() -> None:
    house = generate_preset_house(76, "small")
    plain = generate_house(76)
    assert house.name == plain.name == "house_00076"
    assert house.geometry is not None and plain.geometry is not None
    assert (house.geometry.mesh.positions == plain.geometry.mesh.positions).all()
    assert [i.category for i in house.instances] == [i.category for i in plain.instances]


def test_mp3d_parameters_follow_the_seed_alone() -> None:
    drawn = [MP3D.parameters(seed) for seed in range(40)]
    assert drawn == [MP3D.parameters(seed) for seed in range(40)]
    assert {p.floors for p in drawn} == {1, 2, 3}
    assert all(p.min_rooms == p.max_rooms for p in drawn)
    assert len({p.min_rooms for p in drawn}) > 2  # room counts vary between houses


def test_mp3d_scene_ids_round_trip() -> None:
    scene = procedural_scene_id(76, preset="mp3d")
    assert scene == "vlln/mp3d_00076/mp3d_00076.glb"
    assert procedural_preset(scene) == "mp3d" and canonical_seed(scene) == 76
    assert procedural_preset("vlln/house_00076_2f/house_00076_2f.glb") == "small"
    assert not is_procedural("vlln/mp3d_00076_2f/mp3d_00076_2f.glb")  # storeys come from the seed
    assert not is_procedural("vlln/mp3d_00076/house_00076.glb")
    with pytest.raises(ConfigError, match="spelled 'vlln/mp3d_00076"):
        canonical_seed("vlln/mp3d_76")


def test_an_mp3d_house_is_built_from_its_scene_id() -> None:
    scene = procedural_scene_id(3, preset="mp3d")
    house = procedural_house(scene)
    assert house_scene_id(house) == scene
    levels = {room.level for room in house.rooms}
    assert len(levels) == MP3D.parameters(3).floors
    assert len(house.rooms) == MP3D.parameters(3).min_rooms * len(levels)


def test_fewer_categories_make_more_same_category_distractors() -> None:
    def kinds(variety: float) -> tuple[int, float]:
        house = generate_house(5, HouseParameters(category_variety=variety))
        categories = [inst.category for inst in house.instances]
        return len(set(categories)), len(categories) / len(set(categories))

    full, narrow = kinds(1.0), kinds(0.3)
    assert narrow[0] < full[0] and narrow[1] > full[1]
    assert kinds(0.3) == narrow  # seeded


def test_unknown_presets_and_variety_are_refused_with_the_choices() -> None:
    with pytest.raises(ConfigError, match="choose one of: small, mp3d"):
        preset("hm3d")
    with pytest.raises(HouseParametersError, match="category_variety"):
        HouseParameters(category_variety=0.0).validate()


def test_repeats_multiply_only_what_comes_in_numbers() -> None:
    def counts(repeats: float) -> dict[str, int]:
        house = generate_house(8, HouseParameters(repeats=repeats))
        found: dict[str, int] = {}
        for inst in house.instances:
            found[inst.category] = found.get(inst.category, 0) + 1
        return found

    plain, doubled = counts(1.0), counts(2.5)
    many = ("chair", "book", "picture", "pillow", "towel")
    assert sum(doubled.get(c, 0) for c in many) > 1.5 * sum(plain.get(c, 0) for c in many)
    beds = (plain.get("bed", 0), doubled.get("bed", 0))
    assert beds[0] == beds[1]  # one bed a bedroom, whatever the repeats


def test_a_house_made_again_is_a_copy_of_the_first_that_callers_may_change() -> None:
    first = generate_preset_house(77, "small")
    assert first.geometry is not None
    first.instances.clear()
    first.geometry.mesh.positions[:] = 0.0
    again = generate_preset_house(77, "small")
    fresh = generate_house(77)
    assert again is not first and again.name == "house_00077"
    assert [i.category for i in again.instances] == [i.category for i in fresh.instances]
    assert again.geometry is not None and fresh.geometry is not None
    assert (again.geometry.mesh.positions == fresh.geometry.mesh.positions).all()
    assert generate_preset_house(77, "small", floors=2).name == "house_00077_2f"
