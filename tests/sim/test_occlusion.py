"""Occlusion culling: what a depth image hides, and a culled scan renders the same images."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from tests.sim import scenes
from vlln.sim import renderer as renderer_module
from vlln.sim.camera import CameraSpec
from vlln.sim.occlusion import BLOCK, FarthestDepth, hidden_boxes
from vlln.sim.renderer import Renderer
from vlln.sim.simulator import Simulator
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.mesh import Mesh
from vlln.world.scans import export_scene, import_scene, with_subdivided_mesh

ORIGIN = (0.0, 0.0, 0.0)
MAX_DEPTH = 10.0


def test_farthest_depth_never_reads_nearer_than_the_rectangle_holds() -> None:
    rng = np.random.default_rng(0)
    depth = rng.uniform(0.5, 12.0, (60, 90)).astype(np.float32)
    depth[rng.random(depth.shape) < 0.01] = 0.0  # nothing drawn there
    truth = np.where((depth <= 0) | (depth >= MAX_DEPTH), np.inf, depth)
    farthest = FarthestDepth(depth, MAX_DEPTH)
    rows = np.sort(rng.integers(0, 60, (300, 2)), axis=1)
    cols = np.sort(rng.integers(0, 90, (300, 2)), axis=1)
    got = farthest.maximum(rows[:, 0], rows[:, 1], cols[:, 0], cols[:, 1])
    for k in range(300):
        rect = truth[rows[k, 0] : rows[k, 1] + 1, cols[k, 0] : cols[k, 1] + 1]
        assert got[k] >= rect.max()
    # One whole block is read exactly.
    one = farthest.maximum(*(np.array([v]) for v in (BLOCK, 2 * BLOCK - 1, 0, BLOCK - 1)))
    assert one[0] == truth[BLOCK : 2 * BLOCK, :BLOCK].max()


def test_boxes_wholly_behind_a_wall_are_hidden_and_no_others() -> None:
    spec = CameraSpec(width=160, height=120)
    wall = scenes.wall(-3.0, -3.0, 3.0, -3.0)  # 6 m wide, in front of the camera
    with Renderer(wall, spec) as renderer:
        depth = FarthestDepth(renderer.render(ORIGIN, 0.0).depth, spec.max_depth)
    boxes = {
        "behind": ((-0.5, 0.5, -6.0), (0.5, 1.5, -5.0)),
        "in front": ((-0.5, 0.5, -2.0), (0.5, 1.5, -1.0)),
        "behind, seen above the wall": ((-0.5, 5.6, -9.0), (0.5, 6.0, -8.0)),
        "around the camera": ((-0.5, 0.5, -0.5), (0.5, 2.0, 0.5)),
        "reaching through the wall": ((-0.5, 0.5, -5.0), (0.5, 1.5, -2.5)),
    }
    lows = np.array([low for low, _ in boxes.values()])
    highs = np.array([high for _, high in boxes.values()])
    hidden = hidden_boxes(depth, spec, ORIGIN, 0.0, 0.0, lows, highs)
    assert dict(zip(boxes, hidden.tolist(), strict=True)) == {
        "behind": True,
        "in front": False,
        "behind, seen above the wall": False,
        "around the camera": False,
        "reaching through the wall": False,
    }


@pytest.fixture(scope="module")
def scan(tmp_path_factory: pytest.TempPathFactory) -> Mesh:
    """A small house exported as a Matterport3D scan with every triangle split in four, and
    imported back: a scan's many small triangles, with walls that hide most of them."""
    house = generate_house(7, HouseParameters(min_rooms=3, max_rooms=4))
    folder = export_scene(with_subdivided_mesh(house, 1), tmp_path_factory.mktemp("scan"), "mp3d")
    imported, _ = import_scene(Path(folder))
    assert imported.geometry is not None
    return imported.geometry.mesh


def test_occlusion_culling_draws_fewer_triangles_and_the_same_images(
    scan: Mesh, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The scene is small, so the culling starts at a lower triangle count than for a scan.
    monkeypatch.setattr(renderer_module, "OCCLUSION_MIN", 2_000)
    monkeypatch.setattr(renderer_module, "NEAR_PASS_TRIANGLES", 2_000)
    spec = CameraSpec(width=320, height=240)
    house = generate_house(7, HouseParameters(min_rooms=3, max_rooms=4))
    with Simulator(house) as sim:
        rng = np.random.default_rng(1)
        points = [sim.grid.sample_navigable_point(rng) for _ in range(8)]
    culled, plain = Renderer(scan, spec), Renderer(scan, spec)
    plain.occlusion_culling = False
    drawn = []
    with culled, plain:
        for k, (x, z) in enumerate(points):
            pose = ((x, 0.0, z), k * 0.8, -0.3 if k % 2 else 0.0)
            a, b = culled.render(*pose), plain.render(*pose)
            drawn.append((len(culled.last_drawn_corners()), len(plain.last_drawn_corners())))
            assert np.count_nonzero(b.instance_ids) > 0.9 * b.instance_ids.size
            assert np.mean(a.instance_ids == b.instance_ids) >= 0.999
            assert np.mean(np.all(a.rgb == b.rgb, axis=2)) >= 0.999
            assert np.mean(a.depth == b.depth) >= 0.999
    with_culling, without = np.sum(drawn, axis=0)
    assert with_culling < 0.7 * without
