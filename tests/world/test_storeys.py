"""A two-storey house: one scope per floor in its scene summary, and one map panel per floor."""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib.pyplot as plt
import pytest

from vlln.sim.simulator import Simulator
from vlln.viz.topdown import ROOM_LABEL, house_figure
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House
from vlln.world.scene_summary import export_scene_summary, import_scene_summary

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)


@pytest.fixture(scope="module")
def house() -> House:
    return generate_house(1, SMALL_TWO_STOREYS)


@pytest.mark.slow
def test_three_storeys_have_two_flights_apart() -> None:
    house = generate_house(1, HouseParameters(floors=3))
    assert house.name == "house_00001_3f"
    flights = house.instances_of("stairs")
    assert [(f.box.min[1], round(f.box.max[1], 6)) for f in flights] == [(0.0, 2.8), (2.8, 5.6)]
    a, b = (f.box for f in flights)
    apart = a.max[0] <= b.min[0] or b.max[0] <= a.min[0] or a.max[2] <= b.min[2]
    assert apart or b.max[2] <= a.min[2]
    assert sorted({room.level for room in house.rooms}) == [0, 1, 2]


def test_the_scene_summary_has_one_scope_per_floor(house: House, tmp_path: Path) -> None:
    scene = export_scene_summary(house, tmp_path)
    regions = json.loads((scene / "region_dict.json").read_text(encoding="utf-8"))
    assert list(regions) == [f"{house.name}_0", f"{house.name}_1"]
    for level, scope in enumerate(regions):
        assert [r["id"] for r in regions[scope]] == [
            room.id for room in house.rooms if room.level == level
        ]
    objects = json.loads((scene / "object_dict.json").read_text(encoding="utf-8"))
    levels = {room.id: room.level for room in house.rooms}
    for inst in house.instances:
        assert objects[str(inst.id)]["scope"] == f"{house.name}_{levels[inst.room_id]}"
    back = import_scene_summary(scene)
    assert back.name == house.name
    assert [(r.id, r.level, r.type) for r in back.rooms] == [
        (r.id, r.level, r.type) for r in house.rooms
    ]
    assert [(i.id, i.room_id, i.category) for i in back.instances] == [
        (i.id, i.room_id, i.category) for i in house.instances
    ]


def test_the_map_has_one_panel_per_floor(house: House) -> None:
    with Simulator(house) as sim:
        figure = house_figure(house, sim.nav)
    try:
        assert [ax.get_title() for ax in figure.axes] == ["ground floor", "first floor"]
        for level, ax in enumerate(figure.axes):
            labels = [t.get_text() for t in ax.texts if t.get_gid() == ROOM_LABEL]
            expected = [f"{r.type}\n#{r.id}" for r in house.rooms if r.level == level]
            assert labels == expected
            # The staircase is drawn on both floors it joins; the navigable area too.
            assert any(t.get_text() == "stairs" for t in ax.texts)
            assert len(ax.images) == 1
    finally:
        plt.close(figure)
