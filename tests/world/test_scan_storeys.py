"""Scanned scenes of houses with several storeys: the export and import keep the storeys and
the stairs, so the agent climbs in the imported scene as in the original."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from vlln.sim.simulator import Simulator
from vlln.tasks.episode import Episode, write_episodes
from vlln.tasks.generation import generate_house_episodes
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House, Room
from vlln.world.scans import export_scene, import_scene
from vlln.world.scans.build import on_storeys
from vlln.world.scans.flights import flight_problem
from vlln.world.scans.gltf import write_glb

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)
CELL = 0.05  # m: the simulator's cell size


@pytest.fixture(scope="module")
def original() -> Iterator[Simulator]:
    with Simulator(generate_house(1, SMALL_TWO_STOREYS)) as sim:
        yield sim


@pytest.fixture(scope="module", params=["mp3d", "hm3d"])
def scene(
    request: pytest.FixtureRequest, original: Simulator, tmp_path_factory: pytest.TempPathFactory
) -> tuple[Path, House]:
    """The scene folder of one style, and the house imported from it."""
    folder = export_scene(original.house, tmp_path_factory.mktemp(request.param), request.param)
    back, report = import_scene(folder)
    assert report.flights_left_out == {} and report.unmapped == []
    return folder, back


def test_rooms_come_back_on_their_storeys_with_the_stairs(
    original: Simulator, scene: tuple[Path, House]
) -> None:
    house, (_, back) = original.house, scene
    assert [(r.id, r.type, r.level) for r in back.rooms] == [
        (r.id, r.type, r.level) for r in house.rooms
    ]
    assert [r.floor_y for r in back.rooms] == pytest.approx([r.floor_y for r in house.rooms])
    (flight,) = house.instances_of("stairs")
    (copy,) = back.instances_of("stairs")
    assert (copy.id, copy.room_id) == (flight.id, flight.room_id)
    assert np.allclose(copy.box.min, flight.box.min, atol=1e-3)
    assert np.allclose(copy.box.max, flight.box.max, atol=1e-3)


def test_distances_across_storeys_agree(original: Simulator, scene: tuple[Path, House]) -> None:
    storeys = original.storeys
    assert storeys is not None
    rng = np.random.default_rng(0)
    component = storeys.largest_component()
    with Simulator(scene[1]) as copy:
        assert copy.storeys is not None and len(copy.storeys.grids) == 2
        for mine, theirs in zip(storeys.grids, copy.storeys.grids, strict=True):
            assert np.array_equal(mine.navigable, theirs.navigable)
        crossing = 0
        for _ in range(6):
            start, goal = (storeys.sample_navigable_point(rng, component) for _ in range(2))
            crossing += storeys.level_of(start[1]) != storeys.level_of(goal[1])
            x, y, z = start
            d0 = original.distance_field([goal]).distance(x, z, y)
            d1 = copy.distance_field([goal]).distance(x, z, y)
            assert d1 == pytest.approx(d0, abs=CELL)
        assert crossing >= 2


@pytest.mark.slow
@pytest.mark.parametrize("style", ["mp3d", "hm3d"])
def test_three_storeys_come_back_with_both_flights(style: str, tmp_path: Path) -> None:
    house = generate_house(1, replace(SMALL_TWO_STOREYS, floors=3))
    back, report = import_scene(export_scene(house, tmp_path, style))
    assert report.flights_left_out == {}
    assert [(r.id, r.level) for r in back.rooms] == [(r.id, r.level) for r in house.rooms]
    assert [r.floor_y for r in back.rooms] == pytest.approx([r.floor_y for r in house.rooms])
    assert [i.id for i in back.instances_of("stairs")] == [
        i.id for i in house.instances_of("stairs")
    ]
    with Simulator(house) as original, Simulator(back) as copy:
        assert original.storeys is not None and copy.storeys is not None
        assert copy.storeys.floor_ys == pytest.approx(original.storeys.floor_ys)
        for mine, theirs in zip(original.storeys.grids, copy.storeys.grids, strict=True):
            assert np.array_equal(mine.navigable, theirs.navigable)
        labels, _ = copy.storeys.components()  # one walk reaches every storey
        nodes = np.flatnonzero(labels == copy.storeys.largest_component())
        assert set((nodes // (labels.size // 3)).tolist()) == {0, 1, 2}


@pytest.fixture(scope="module")
def crossing_episode(original: Simulator) -> Episode:
    """The shortest IGN episode whose target stands on the other storey than its start."""
    storeys = original.storeys
    assert storeys is not None

    def target_level(episode: Episode) -> int:
        target = original.house.instance(int(episode.instruction.instance_id[0]))
        return storeys.level_under(target.box.min[1])

    made = generate_house_episodes(original, np.random.default_rng(0))
    crossing = [e for e in made.ign if storeys.level_of(e.start_position[1]) != target_level(e)]
    return min(crossing, key=lambda episode: episode.info["geodesic_distance"])


@pytest.mark.slow
def test_the_expert_climbs_to_its_target_in_the_imported_scene(
    crossing_episode: Episode, scene: tuple[Path, House], tmp_path: Path
) -> None:
    from vlln.cli import main
    from vlln.eval.results import read_records

    folder, _ = scene
    episode = crossing_episode
    name = folder.name
    path = tmp_path / "val_ign.json.gz"
    write_episodes(path, [replace(episode, scene_id=f"{folder.parent.name}/{name}/{name}.glb")])
    out = tmp_path / "run"
    args = ["eval", "--agent", "expert", "--task", "ign", "--episode-file", str(path)]
    assert main([*args, "--scenes", str(folder.parent), "--out", str(out), "--quiet"]) == 0
    (record,) = read_records(next(out.rglob("*.jsonl")))
    assert record.error is None and record.end_reason == "stop"
    assert record.geodesic_start == pytest.approx(episode.info["geodesic_distance"], abs=CELL)
    assert record.geodesic_trace[-1] < 0.25
    assert record.stop_instance_id == int(episode.instruction.instance_id[0])


def test_hm3d_storeys_come_from_the_geometry_alone(original: Simulator, tmp_path: Path) -> None:
    folder = export_scene(original.house, tmp_path, "hm3d")
    for summary in ("object_dict.json", "region_dict.json"):
        (folder / summary).unlink()
    back, _ = import_scene(folder)
    assert [(r.id, r.level) for r in back.rooms] == [(r.id, r.level) for r in original.house.rooms]
    assert [i.id for i in back.instances_of("stairs")] == [
        i.id for i in original.house.instances_of("stairs")
    ]


def test_a_flight_with_noisy_treads_is_left_out_and_said_so(
    original: Simulator, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    house = original.house
    folder = export_scene(house, tmp_path, "mp3d")
    mesh = house.geometry.mesh if house.geometry else None
    assert mesh is not None
    (flight,) = house.instances_of("stairs")
    triangles = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
    heights = triangles[:, :, 1]
    inner = (mesh.instance_ids.reshape(-1, 3) == flight.id) & (heights > 0.0) & (heights < 2.7)
    noise = np.random.default_rng(0).normal(0.0, 0.01, heights.shape)
    triangles[:, :, 1] = np.where(inner, heights + noise, heights)  # a scan's uneven treads
    write_glb(folder / f"{house.name}.glb", triangles, mesh.colors)
    with caplog.at_level(logging.WARNING):
        back, report = import_scene(folder)
    assert list(report.flights_left_out) == [flight.id]
    assert "flat treads" in report.flights_left_out[flight.id]
    assert f"the stairs {flight.id} cannot be climbed" in caplog.text
    assert back.instances_of("stairs") == []
    with Simulator(back) as sim:  # the storeys stay apart, each one walkable on its own
        assert sim.storeys is not None and len(sim.storeys.grids) == 2
        labels, count = sim.storeys.components()
        cells = labels.size // 2
        assert count >= 2
        assert not set(labels[:cells][labels[:cells] > 0]) & set(labels[cells:])


def test_a_flight_must_join_a_floor_to_the_next(original: Simulator) -> None:
    mesh = original.house.geometry.mesh if original.house.geometry else None
    assert mesh is not None
    (flight,) = original.house.instances_of("stairs")
    triangles = mesh.positions.reshape(-1, 3, 3)[mesh.instance_ids[::3] == flight.id]
    steps = triangles.astype(np.float64)
    assert flight_problem(steps, [0.0, 2.8]) is None
    assert "is not the floor of the storey above" in str(flight_problem(steps, [0.0]))
    assert "is on no storey's floor" in str(flight_problem(steps, [0.5, 2.8]))
    treads = steps[np.ptp(steps[:, :, 1], axis=1) == 0.0]
    every_other = treads[np.round(treads[:, 0, 1] / 0.2).astype(int) % 2 == 0]  # 0.4 m apart
    assert "a step rises 0.40 m" in str(flight_problem(every_other, [0.4, 2.8]))


def test_a_scans_uneven_room_floors_make_one_floor_per_storey() -> None:
    square = ((0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0))
    floors = [0.02, -0.01, 0.0, 2.79, 2.83]
    rooms = [Room(k, "other", square, floor_y=y) for k, y in enumerate(floors)]
    placed = on_storeys(rooms)
    assert [r.level for r in placed] == [0, 0, 0, 1, 1]
    assert [r.floor_y for r in placed] == pytest.approx([0.0, 0.0, 0.0, 2.81, 2.81])


def test_an_object_without_a_region_goes_to_the_room_of_its_storey(
    original: Simulator, tmp_path: Path
) -> None:
    house = original.house
    folder = export_scene(house, tmp_path, "mp3d")
    for summary in ("object_dict.json", "region_dict.json"):
        (folder / summary).unlink()
    levels = {room.id: room.level for room in house.rooms}
    moved = [next(i for i in house.instances if levels[i.room_id] == level) for level in (0, 1)]
    path = folder / f"{house.name}.house"
    lines = path.read_text(encoding="utf-8").splitlines()
    for k, line in enumerate(lines):
        fields = line.split()
        if fields[0] == "O" and int(fields[1]) in {i.id for i in moved}:
            lines[k] = " ".join([*fields[:2], "99", *fields[3:]])  # a region the file lacks
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    back, _ = import_scene(folder)
    assert [back.instance(i.id).room_id for i in moved] == [i.room_id for i in moved]
