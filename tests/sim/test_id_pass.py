"""The id-only pass draws exactly the instance ids of the full pass, for any pose and camera."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from vlln.errors import RendererUnavailableError
from vlln.sim.camera import CameraSpec
from vlln.sim.id_pass import gl_finish, id_vertex_format
from vlln.sim.renderer import Renderer
from vlln.sim.shaders import VERTEX_DTYPE, VERTEX_FORMAT
from vlln.sim.simulator import Simulator
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.mesh import Mesh

SMALL = HouseParameters(min_rooms=4, max_rooms=5, min_area=60.0, max_area=90.0)


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    with Simulator(generate_house(23, SMALL)) as simulator:
        yield simulator


def poses(
    sim: Simulator, count: int, seed: int
) -> list[tuple[tuple[float, float, float], float, float]]:
    """Random navigable poses looking in every direction, level and tilted."""
    grid = sim.grid
    rng = np.random.default_rng(seed)
    chosen = []
    for _ in range(count):
        x, z = grid.sample_navigable_point(rng, grid.largest_component())
        yaw = float(rng.uniform(-math.pi, math.pi))
        tilt = float(rng.choice([0.0, -0.52, 0.35]))
        chosen.append(((x, grid.floor_y, z), yaw, tilt))
    return chosen


@pytest.mark.slow
def test_the_id_pass_equals_the_full_pass_on_many_poses(sim: Simulator) -> None:
    renderer = sim.renderer
    seen: set[int] = set()
    for position, yaw, tilt in poses(sim, 80, seed=3):
        ids = renderer.render_instance_ids(position, yaw, tilt)
        full = renderer.render(position, yaw, tilt).instance_ids
        assert np.array_equal(ids, full), (position, yaw, tilt)
        seen.update(np.unique(ids).tolist())
    assert len(seen) > 10  # the poses saw many objects and the structure, not blank walls


def test_the_id_pass_follows_a_change_of_camera(sim: Simulator) -> None:
    renderer = sim.renderer
    (position, yaw, tilt), *_ = poses(sim, 1, seed=4)
    renderer.render_instance_ids(position, yaw, tilt)  # the pass exists for the old size
    try:
        renderer.set_camera(CameraSpec(width=200, height=150, hfov_deg=90.0))
        ids = renderer.render_instance_ids(position, yaw, tilt)
        assert ids.shape == (150, 200)
        assert np.array_equal(ids, renderer.render(position, yaw, tilt).instance_ids)
    finally:
        renderer.set_camera(CameraSpec())


def test_an_empty_mesh_has_no_ids_and_a_closed_renderer_refuses() -> None:
    renderer = Renderer(Mesh.empty(), CameraSpec(width=64, height=48))
    ids = renderer.render_instance_ids((0.0, 0.0, 0.0), 0.0)
    assert ids.shape == (48, 64) and not ids.any()
    renderer.close()
    with pytest.raises(RendererUnavailableError, match="closed"):
        renderer.render_instance_ids((0.0, 0.0, 0.0), 0.0)


def test_the_id_format_reads_position_and_instance_of_a_whole_record() -> None:
    fmt = id_vertex_format()
    assert fmt.split()[0] == "3f" and fmt.split()[-1] == "1i"
    sizes = {"f": 4, "i": 4, "x": 1}
    total = sum(int(part[:-1]) * sizes[part[-1]] for part in fmt.split())
    assert total == VERTEX_DTYPE.itemsize
    assert len(VERTEX_FORMAT.split()) == len(VERTEX_DTYPE.names or ())


def test_the_wait_for_the_rasteriser_is_found_on_this_machine() -> None:
    assert gl_finish() is not None  # else every id frame would hold the interpreter lock
