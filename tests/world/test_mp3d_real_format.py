"""A scene in the real Matterport3D format (tests/world/mp3d_scene.py, made from the format's
description, not by vlln's exporter) imports as scanned: its ordinary stairs join the storeys,
mpcat40 decides what a flight is, and void annotations are no objects."""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from tests.world import mp3d_scene
from vlln.sim.simulator import Simulator
from vlln.world.model import House
from vlln.world.scans import ImportReport, import_scene
from vlln.world.scans.categories import is_flight, is_structure, is_void, mpcat40_group
from vlln.world.scans.flights import flight_problem
from vlln.world.scene_summary import export_scene_summary

TOKENS = {"H": 29, "L": 18, "R": 20, "S": 22, "V": 13, "P": 13, "I": 41, "C": 11, "O": 24, "E": 19}


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return mp3d_scene.write_scene(tmp_path_factory.mktemp("mp3d"))


@pytest.fixture(scope="module")
def imported(folder: Path) -> tuple[House, ImportReport]:
    return import_scene(folder)


@pytest.fixture(scope="module")
def sim(imported: tuple[House, ImportReport]) -> Iterator[Simulator]:
    with Simulator(imported[0]) as simulator:
        yield simulator


def test_the_house_file_is_in_the_real_format(folder: Path) -> None:
    lines = (folder / f"{folder.name}.house").read_text(encoding="utf-8").splitlines()
    assert lines[0] == "ASCII 1.1"
    kinds = [line.split()[0] for line in lines[1:]]
    order = list(dict.fromkeys(kinds))
    assert order == ["H", "L", "R", "S", "V", "P", "I", "C", "O", "E"]
    assert kinds == sorted(kinds, key=order.index)  # each kind in one block
    for line in lines[1:]:
        assert len(line.split()) == TOKENS[line.split()[0]], line
    header = lines[1].split()
    counts = Counter(kinds)
    # H: #images #panoramas #vertices #surfaces #segments #objects #categories #regions
    assert [int(v) for v in header[3:11]] == [
        counts["I"], counts["P"], counts["V"], counts["S"], counts["E"], counts["O"],
        counts["C"], counts["R"],
    ]  # fmt: skip
    steps = next(line.split() for line in lines if line.startswith("C") and "steps" in line)
    assert steps[3:6] == ["steps", "16", "stairs"]


def test_stairs_whose_last_rise_steps_onto_the_floor_join_the_storeys(
    imported: tuple[House, ImportReport], sim: Simulator
) -> None:
    house, report = imported
    assert report.flights_left_out == {}
    flight = house.instance(mp3d_scene.FLIGHT_ID)
    assert (flight.category, flight.fine_category) == ("stairs", "steps")
    mesh = house.geometry.mesh if house.geometry else None
    assert mesh is not None
    steps = mesh.positions.reshape(-1, 3, 3)[mesh.instance_ids[::3] == flight.id]
    top_tread = mp3d_scene.UPPER - mp3d_scene.RISE
    assert steps[:, :, 1].max() == pytest.approx(top_tread, abs=1e-5)  # the last rise is not its
    storeys = sim.storeys
    assert storeys is not None and storeys.floor_ys == pytest.approx((0.0, mp3d_scene.UPPER))
    labels, _ = storeys.components()
    cells = labels.size // 2
    largest = labels == storeys.largest_component()
    assert largest[:cells].sum() > 0.9 * (labels[:cells] > 0).sum()  # all of the ground floor
    assert largest[cells:].sum() > 0.9 * (labels[cells:] > 0).sum()  # and all of the upper one


def test_the_way_upstairs_climbs_the_flight(sim: Simulator) -> None:
    foot = mp3d_scene.to_vlln(0.6, mp3d_scene.FOOT_Y - 0.5, 0.0)
    head = mp3d_scene.to_vlln(0.6, mp3d_scene.HEAD_Y + 0.5, mp3d_scene.UPPER)
    field = sim.distance_field([head])
    run = mp3d_scene.HEAD_Y - mp3d_scene.FOOT_Y + 1.0
    climb = float(np.hypot(run, mp3d_scene.UPPER))
    assert climb <= field.distance(foot[0], foot[2], foot[1]) <= climb + 0.5


def test_void_categories_are_no_objects(
    imported: tuple[House, ImportReport], tmp_path: Path
) -> None:
    house, report = imported
    void = {mp3d_scene.REMOVE_ID, mp3d_scene.UNKNOWN_ID, mp3d_scene.NO_CATEGORY_ID}
    ids = {inst.id for inst in house.instances}
    assert not ids & void
    assert ids == {2, 3, mp3d_scene.FLIGHT_ID, mp3d_scene.BED_ID, 7, 8}  # walls, floors: shell
    assert report.void_objects == 3 and report.unmapped == []
    words = {inst.category for inst in house.instances} | {
        inst.fine_category for inst in house.instances
    }
    assert not words & {"remove", "unknown", "void", ""}
    export_scene_summary(house, tmp_path)
    summary = json.loads(next(tmp_path.rglob("object_dict.json")).read_text(encoding="utf-8"))
    assert "remove" not in json.dumps(summary) and "unknown" not in json.dumps(summary)


def test_mpcat40_decides_with_the_raw_word_as_fallback() -> None:
    assert mpcat40_group(16, "stairs") == "stairs"
    assert mpcat40_group(0, "stairs") is None  # older vlln exports: "0 <raw word>"
    assert mpcat40_group(42, "stairs") is None
    assert is_flight("steps", "stairs") and is_flight("step", "stairs")
    assert is_flight("emergency exit", "stairs")  # mpcat40 wins over the raw word
    assert not is_flight("stair#rail", "railing") and not is_flight("staircase trim", "misc")
    assert is_flight("staircase", None) and is_flight("steps", None)  # no group: the raw word
    assert is_void("remove", "void") and is_void("remove#/#behind", "void")
    assert is_void("unknown", "misc") and is_void("", None) and is_void("wires", "unlabeled")
    assert not is_void("couch", "sofa") and not is_void("steps", "stairs")
    assert is_structure("floor#/#upstairs#room", "floor") and is_structure("wall", None)
    assert not is_structure("couch", "sofa")


def _steps(treads: int, rise: float = 0.2, tread: float = 0.25) -> np.ndarray:
    """Treads 1..``treads`` of a flight along z (two triangles each, y up), no risers."""
    quads = []
    for k in range(1, treads + 1):
        y, z0, z1 = k * rise, k * tread, (k + 1) * tread
        quads += [
            [(0.0, y, z0), (1.0, y, z1), (1.0, y, z0)],  # up-facing (y up, z toward you)
            [(0.0, y, z0), (0.0, y, z1), (1.0, y, z1)],
        ]
    return np.array(quads, float)


def test_a_flight_arrives_when_its_last_rise_steps_onto_the_floor() -> None:
    floors = [0.0, 2.8]
    assert flight_problem(_steps(14), floors) is None  # the top tread level with the floor
    assert flight_problem(_steps(13), floors) is None  # treads up to 2.6, a rise onto 2.8
    assert flight_problem(_steps(12), floors) == (
        "its top (2.400 m) is not the floor of the storey above its foot (0.000, 2.800 m)"
    )  # 0.4 m below the floor: no step onto it
    assert flight_problem(_steps(13)[2:], floors) == (
        "its foot (0.400 m) is on no storey's floor (0.000, 2.800 m)"
    )
