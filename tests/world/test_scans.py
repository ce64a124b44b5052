"""Scanned-scene import: a procedural house exported as Matterport3D and HM3D folders comes
back with the same instances, rooms, distances and pictures."""

from __future__ import annotations

import json
import struct
from pathlib import Path

import numpy as np
import pytest

from vlln.errors import DataFormatError
from vlln.sim.geodesic import GeodesicField
from vlln.sim.simulator import Simulator
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House
from vlln.world.scans import export_scene, import_scene, map_category
from vlln.world.scans.gltf import read_glb

SMALL = HouseParameters(min_rooms=3, max_rooms=4, min_area=35.0, max_area=55.0)


@pytest.fixture(scope="module")
def house() -> House:
    return generate_house(7, SMALL)


@pytest.fixture(scope="module", params=["mp3d", "hm3d"])
def imported(
    request: pytest.FixtureRequest, house: House, tmp_path_factory: pytest.TempPathFactory
) -> House:
    folder = export_scene(house, tmp_path_factory.mktemp(request.param), request.param)
    back, report = import_scene(folder)
    assert report.instances == len(house.instances) and report.unmapped == []
    return back


def test_instances_come_back_with_category_room_and_position(house: House, imported: House) -> None:
    back = {inst.id: inst for inst in imported.instances}
    assert sorted(back) == sorted(inst.id for inst in house.instances)
    for inst in house.instances:
        other = back[inst.id]
        assert (other.category, other.room_id) == (inst.category, inst.room_id)
        assert np.linalg.norm(np.subtract(other.position, inst.position)) < 0.05


def test_rooms_come_back(house: House, imported: House) -> None:
    assert [(r.id, r.type) for r in imported.rooms] == [(r.id, r.type) for r in house.rooms]
    for mine, theirs in zip(house.rooms, imported.rooms, strict=True):
        assert np.allclose(mine.polygon, theirs.polygon, atol=1e-3)
        assert theirs.floor_y == pytest.approx(mine.floor_y, abs=1e-3)


@pytest.mark.slow
def test_geodesics_and_instance_images_agree(house: House, imported: House) -> None:
    rng = np.random.default_rng(0)
    with Simulator(house) as original, Simulator(imported) as copy:
        component = original.grid.largest_component()
        pairs = [
            (original.grid.sample_navigable_point(rng, component) for _ in range(2))
            for _ in range(100)
        ]
        ratios = []
        for start, goal in pairs:
            d0 = GeodesicField(original.grid, [goal]).distance(*start)
            d1 = GeodesicField(copy.grid, [goal]).distance(*start)
            ratios.append(abs(d1 - d0) / max(d0, 0.5))
        assert max(ratios) <= 0.05
        agreement = []
        for _ in range(20):
            x, z = original.grid.sample_navigable_point(rng, component)
            yaw = float(rng.uniform(-np.pi, np.pi))
            a = original.renderer.render((x, 0.0, z), yaw).instance_ids
            b = copy.renderer.render((x, 0.0, z), yaw).instance_ids
            agreement.append(float(np.mean(a == b)))
        assert min(agreement) >= 0.9


def test_category_mapping_knows_synonyms_and_reports_the_rest() -> None:
    assert map_category("couch") == ("couch", True)
    assert map_category("sofa") == ("couch", True)
    assert map_category("tv_monitor") == ("tv", True)
    assert map_category("Chair") == ("chair", True)
    assert map_category("chairs") == ("chair", True)
    assert map_category("misc_thing") == ("misc thing", False)


def test_basis_textures_are_refused_naming_the_plain_file(tmp_path: Path) -> None:
    document = json.dumps({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_texture_basisu"]})
    chunk = document.encode() + b" " * (-len(document) % 4)
    header = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(chunk))
    path = tmp_path / "abc.basis.glb"
    path.write_bytes(header + struct.pack("<I4s", len(chunk), b"JSON") + chunk)
    with pytest.raises(DataFormatError, match=r"Basis Universal.*use abc\.glb"):
        read_glb(path)


def test_a_folder_without_annotations_is_a_clear_error(tmp_path: Path) -> None:
    (tmp_path / "s").mkdir()
    with pytest.raises(DataFormatError, match=r"s\.house .*semantic\.txt"):
        import_scene(tmp_path / "s")
