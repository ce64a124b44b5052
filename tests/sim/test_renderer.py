"""The renderer: geometry of depth and ids, camera changes, determinism, material looks."""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator

import numpy as np
import pytest
from numpy.typing import NDArray

from vlln.errors import ConfigError, RendererUnavailableError
from vlln.sim import gl_context
from vlln.sim.camera import CameraSpec
from vlln.sim.draw_list import DrawList
from vlln.sim.renderer import Frame, Renderer
from vlln.sim.shaders import (
    MATERIAL_LOOKS,
    VERTEX_DTYPE,
    VERTEX_FORMAT,
    interleave_vertices,
)
from vlln.world.materials import MATERIALS, material_index
from vlln.world.mesh import Mesh, MeshBuilder
from vlln.world.model import StructureId

ORIGIN = (0.0, 0.0, 0.0)
GREY = (0.5, 0.5, 0.5)
BOX_ID = 7


def box_scene(distance: float = 2.5, size: float = 1.0) -> Mesh:
    """A cube whose front face is ``distance`` m straight ahead of a camera at the origin."""
    builder = MeshBuilder()
    centre = (0.0, CameraSpec().height_m, -(distance + size / 2.0))
    builder.box(centre, (size, size, size), GREY, material_index("plastic"))
    return builder.build().with_instance_id(BOX_ID)


def floor_scene() -> Mesh:
    builder = MeshBuilder()
    builder.quad((-20.0, 0.0, 20.0), (40.0, 0.0, 0.0), (0.0, 0.0, -40.0), GREY, 0)
    return builder.build().with_instance_id(StructureId.FLOOR)


@pytest.fixture(scope="module")
def box_renderer() -> Iterator[Renderer]:
    with Renderer(box_scene()) as renderer:
        yield renderer


def centre_value(image: NDArray[np.generic]) -> float:
    """Mean of the 2x2 pixels around the image centre ((w-1)/2, (h-1)/2)."""
    h, w = image.shape[:2]
    return float(image[h // 2 - 1 : h // 2 + 1, w // 2 - 1 : w // 2 + 1].mean())


def test_frame_shapes_and_types(box_renderer: Renderer) -> None:
    frame = box_renderer.render(ORIGIN, 0.0)
    assert frame.rgb.shape == (480, 640, 3) and frame.rgb.dtype == np.uint8
    assert frame.depth.shape == (480, 640) and frame.depth.dtype == np.float32
    assert frame.instance_ids.shape == (480, 640) and frame.instance_ids.dtype == np.int32


def test_box_depth_and_id_at_the_centre(box_renderer: Renderer) -> None:
    frame = box_renderer.render(ORIGIN, 0.0)
    assert centre_value(frame.depth) == pytest.approx(2.5, abs=0.01)
    assert frame.instance_ids[240, 320] == BOX_ID
    assert frame.rgb[240, 320].max() > 0


def test_nothing_drawn_gives_id_zero_and_depth_zero(box_renderer: Renderer) -> None:
    frame = box_renderer.render(ORIGIN, 0.0)
    empty = frame.instance_ids == 0
    assert empty[0, 0] and empty[-1, -1]  # the corners miss the box
    assert np.all(frame.depth[empty] == 0.0)
    assert np.all(frame.rgb[empty] == 0)
    assert np.all(frame.depth[~empty] > 0.0)


def test_far_surfaces_are_clamped_to_max_depth() -> None:
    with Renderer(box_scene(distance=15.0, size=4.0)) as renderer:
        frame = renderer.render(ORIGIN, 0.0)
    assert frame.instance_ids[240, 320] == BOX_ID
    assert frame.depth[240, 320] == pytest.approx(renderer.spec.max_depth)
    assert frame.depth.max() == pytest.approx(renderer.spec.max_depth)


def test_turning_away_hides_the_box(box_renderer: Renderer) -> None:
    frame = box_renderer.render(ORIGIN, math.pi)
    assert not np.any(frame.instance_ids == BOX_ID)


def test_floor_seen_30_degrees_down_has_the_analytic_depth() -> None:
    spec = CameraSpec()
    _, fy, _, cy = spec.intrinsics()
    down = math.radians(30.0)
    with Renderer(floor_scene(), spec) as renderer:
        frame = renderer.render(ORIGIN, 0.7, -down)
    # On the optical axis the z-depth is h / sin(30 deg) = 2.5 m.
    assert centre_value(frame.depth) == pytest.approx(spec.height_m / math.sin(down), abs=0.01)
    # Any pixel: the ray (x, -(v - cy)/fy, -1) in camera axes reaches the floor at this z-depth.
    for v in (240, 300, 470):
        expected = spec.height_m / (math.sin(down) + (v - cy) / fy * math.cos(down))
        assert frame.depth[v, 100] == pytest.approx(expected, abs=0.01)
    # Above the horizon, nothing: the floor id appears only below it.
    assert np.all(frame.instance_ids[:5] == 0)
    assert np.all(frame.instance_ids[-5:] == StructureId.FLOOR)


def test_structure_ids_come_through_unchanged() -> None:
    builder = MeshBuilder()
    builder.quad((-3.0, 0.0, -1.0), (6.0, 0.0, 0.0), (0.0, 2.5, 0.0), GREY, 0)
    wall = builder.build().with_instance_id(StructureId.WALL)
    mesh = Mesh.concatenate([floor_scene(), wall])
    with Renderer(mesh) as renderer:
        ids = renderer.render((0.0, 0.0, 2.0), 0.0, -0.2).instance_ids
    assert set(np.unique(ids)) == {StructureId.FLOOR, StructureId.WALL}


def test_unproject_of_rendered_depth_lands_on_the_box(box_renderer: Renderer) -> None:
    spec = box_renderer.spec
    position, yaw = (1.2, 0.0, 0.0), 0.3  # right of the box, turned left toward it
    frame = box_renderer.render(position, yaw)
    vs, us = np.nonzero(frame.instance_ids == BOX_ID)
    points = spec.unproject(us, vs, frame.depth[vs, us], position, yaw)
    on_front = np.abs(points[:, 2] + 2.5) < 0.01
    on_side = np.abs(points[:, 0] - 0.5) < 0.01
    assert on_front.sum() > 1000 and on_side.sum() > 1000
    assert np.all(on_front | on_side)  # every pixel is on one of the two visible faces
    assert np.all(np.abs(points[on_front, 0]) <= 0.5 + 0.01)
    assert np.all(np.abs(points[:, 1] - spec.height_m) <= 0.5 + 0.01)
    assert np.all((points[on_side, 2] <= -2.5 + 0.01) & (points[on_side, 2] >= -3.5 - 0.01))


@pytest.mark.parametrize(("width", "height", "hfov"), [(320, 240, 79.0), (640, 480, 60.0)])
def test_resolution_and_fov_set_size_and_projected_width(
    box_renderer: Renderer, width: int, height: int, hfov: float
) -> None:
    spec = CameraSpec(width=width, height=height, hfov_deg=hfov)
    box_renderer.set_camera(spec)
    try:
        frame = box_renderer.render(ORIGIN, 0.0)
    finally:
        box_renderer.set_camera(CameraSpec())
    assert frame.rgb.shape == (height, width, 3)
    fx, _, _, _ = spec.intrinsics()
    row = frame.instance_ids[height // 2]
    # A 1 m wide face at 2.5 m spans fx * 1 / 2.5 pixels.
    assert np.count_nonzero(row == BOX_ID) == pytest.approx(fx / 2.5, abs=1.5)


def test_a_second_renderer_with_another_spec_agrees(box_renderer: Renderer) -> None:
    spec = CameraSpec(width=320, height=240)
    with Renderer(box_scene(), spec) as small:
        frame = small.render(ORIGIN, 0.0)
    box_renderer.set_camera(spec)
    try:
        np.testing.assert_array_equal(frame.rgb, box_renderer.render(ORIGIN, 0.0).rgb)
    finally:
        box_renderer.set_camera(CameraSpec())


def test_same_input_renders_byte_identical_frames(box_renderer: Renderer) -> None:
    pose = ((0.3, 0.0, 0.2), 0.25, -0.1)
    first, second = box_renderer.render(*pose), box_renderer.render(*pose)
    for name in ("rgb", "depth", "instance_ids"):
        assert getattr(first, name).tobytes() == getattr(second, name).tobytes()
    with Renderer(box_scene()) as other:
        assert other.render(*pose).rgb.tobytes() == first.rgb.tobytes()


def test_render_into_a_reused_frame(box_renderer: Renderer) -> None:
    out = Frame.allocate(box_renderer.spec)
    result = box_renderer.render(ORIGIN, 0.1, out=out)
    assert result is out
    fresh = box_renderer.render(ORIGIN, 0.1)
    np.testing.assert_array_equal(out.rgb, fresh.rgb)
    np.testing.assert_array_equal(out.depth, fresh.depth)
    with pytest.raises(ConfigError, match=r"out\.rgb"):
        box_renderer.render(ORIGIN, 0.0, out=Frame.allocate(CameraSpec(width=320, height=240)))


def test_fresh_frames_are_independent(box_renderer: Renderer) -> None:
    first = box_renderer.render(ORIGIN, 0.0)
    kept = first.instance_ids.copy()
    box_renderer.render(ORIGIN, math.pi)
    np.testing.assert_array_equal(first.instance_ids, kept)


def test_back_faces_are_culled_only_when_asked() -> None:
    builder = MeshBuilder()
    # Faces +z away from a camera that looks along -z from z = 0: we see its back.
    builder.quad((-1.0, 0.5, -3.0), (0.0, 1.5, 0.0), (2.0, 0.0, 0.0), GREY, 0)
    mesh = builder.build().with_instance_id(3)
    assert mesh.normals[0, 2] == pytest.approx(-1.0)
    with Renderer(mesh) as culling:
        assert not np.any(culling.render(ORIGIN, 0.0).instance_ids == 3)
    with Renderer(mesh, cull_back_faces=False) as two_sided:
        frame = two_sided.render(ORIGIN, 0.0)
    assert frame.instance_ids[240, 320] == 3
    assert frame.depth[240, 320] == pytest.approx(3.0, abs=0.01)


def test_objects_outside_the_view_are_not_drawn() -> None:
    builder = MeshBuilder()
    builder.box((0.0, 1.0, 4.0), (1.0, 1.0, 1.0), GREY, 0)  # behind the camera
    behind = builder.build().with_instance_id(2)
    mesh = Mesh.concatenate([behind, box_scene()])
    draw_list = DrawList.from_vertices(interleave_vertices(mesh))
    indices = draw_list.indices(CameraSpec(), ORIGIN, 0.0, 0.0)
    records = np.frombuffer(draw_list.vertices, VERTEX_DTYPE)
    assert set(records["instance"][indices].tolist()) == {BOX_ID}
    with Renderer(mesh) as renderer:
        turned = renderer.render(ORIGIN, math.pi).instance_ids
    assert np.any(turned == 2) and not np.any(turned == BOX_ID)


def test_an_empty_mesh_renders_nothing() -> None:
    with Renderer(Mesh.empty(), CameraSpec(width=64, height=48)) as renderer:
        frame = renderer.render(ORIGIN, 0.0)
    assert not frame.rgb.any() and not frame.depth.any() and not frame.instance_ids.any()


def test_a_closed_renderer_refuses_to_render() -> None:
    renderer = Renderer(box_scene(), CameraSpec(width=64, height=48))
    renderer.close()
    renderer.close()  # closing twice is harmless
    with pytest.raises(RendererUnavailableError, match="closed"):
        renderer.render(ORIGIN, 0.0)


def test_vertex_buffer_layout_matches_the_format() -> None:
    mesh = box_scene()
    data = interleave_vertices(mesh)
    sizes = {"f": 4, "i": 4}
    stride = sum(int(part[0]) * sizes[part[1]] for part in VERTEX_FORMAT.split())
    assert stride == VERTEX_DTYPE.itemsize
    assert len(data) == len(mesh.positions) * stride
    assert tuple(MATERIAL_LOOKS) == MATERIALS


def test_objects_are_grouped_before_the_structure() -> None:
    mesh = Mesh.concatenate([floor_scene(), box_scene(), floor_scene().with_instance_id(5)])
    ids = np.frombuffer(interleave_vertices(mesh), VERTEX_DTYPE)["instance"]
    runs = [key for key, _ in itertools.groupby(ids.tolist())]
    assert runs == [5, BOX_ID, StructureId.FLOOR]


def test_every_material_looks_different() -> None:
    spec = CameraSpec(width=160, height=120)
    signatures = []
    for index, name in enumerate(MATERIALS):
        builder = MeshBuilder()
        builder.box((0.0, 1.25, -1.0), (2.0, 2.0, 0.2), (0.5, 0.4, 0.3), index, yaw=0.3)
        with Renderer(builder.build().with_instance_id(1), spec) as renderer:
            rgb = renderer.render(ORIGIN, 0.0).rgb.astype(np.float64)
        luminance = rgb.mean(axis=2)
        detail = np.abs(np.diff(luminance, axis=1)).mean()
        signatures.append((name, np.r_[rgb.reshape(-1, 3).mean(axis=0), luminance.std(), detail]))
    for (name_a, a), (name_b, b) in itertools.combinations(signatures, 2):
        assert np.abs(a - b).max() > 2.0, f"{name_a} and {name_b} render alike"


def test_missing_egl_says_which_packages_to_install(monkeypatch: pytest.MonkeyPatch) -> None:
    def no_egl(**options: object) -> None:
        raise Exception("libEGL.so: cannot open shared object file")

    monkeypatch.setattr(gl_context.moderngl, "create_context", no_egl)
    with pytest.raises(RendererUnavailableError, match="libegl1 and libgl1-mesa-dri"):
        Renderer(box_scene())


def test_description_names_the_opengl_renderer(box_renderer: Renderer) -> None:
    vendor, renderer, version = box_renderer.description.split(" | ")
    assert vendor and renderer and version


def test_draw_list_puts_near_objects_first_and_the_structure_last() -> None:
    builder = MeshBuilder()
    builder.box((0.0, 1.0, -8.0), (1.0, 1.0, 1.0), GREY, 0)
    far = builder.build().with_instance_id(1)
    builder = MeshBuilder()
    builder.box((0.5, 1.0, -3.0), (1.0, 1.0, 1.0), GREY, 0)
    near = builder.build().with_instance_id(2)
    mesh = Mesh.concatenate([floor_scene(), far, near])
    draw_list = DrawList.from_vertices(interleave_vertices(mesh))
    indices = draw_list.indices(CameraSpec(), ORIGIN, 0.0, 0.0)
    ids = np.frombuffer(draw_list.vertices, VERTEX_DTYPE)["instance"][indices]
    runs = [key for key, _ in itertools.groupby(ids.tolist())]
    assert runs == [2, 1, StructureId.FLOOR]
    assert len(indices) == len(draw_list.corners)  # everything is in view, each corner once


def test_draw_list_shares_identical_vertices_without_changing_triangles() -> None:
    soup = interleave_vertices(Mesh.concatenate([box_scene(), floor_scene()]))
    draw_list = DrawList.from_vertices(soup)
    unique = np.frombuffer(draw_list.vertices, VERTEX_DTYPE)
    assert len(unique) == 6 * 4 + 4  # a box has 4 corners per face, the floor quad 4
    assert unique[draw_list.corners].tobytes() == soup


def test_unknown_material_index_is_refused() -> None:
    builder = MeshBuilder()
    builder.box((0.0, 1.0, -3.0), (1.0, 1.0, 1.0), GREY, len(MATERIALS))
    with pytest.raises(ConfigError, match="material index 12"):
        Renderer(builder.build())


def test_renderers_sharing_a_process_each_draw_their_own_scene() -> None:
    """Creating, using and closing other renderers must not change what one renders."""
    first = Renderer(box_scene(distance=2.5))
    before = first.render(ORIGIN, 0.0)
    second = Renderer(box_scene(distance=4.0))
    assert centre_value(second.render(ORIGIN, 0.0).depth) == pytest.approx(4.0, abs=0.01)
    second.close()
    after = first.render(ORIGIN, 0.0)
    first.close()
    assert after.instance_ids.tobytes() == before.instance_ids.tobytes()
    assert after.depth.tobytes() == before.depth.tobytes()


def test_long_runs_of_one_id_are_cut_into_chunks_that_draw_the_same_image(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from vlln.sim import draw_list

    build = MeshBuilder()
    for i, j in itertools.product(range(40), range(40)):  # 3,200 floor triangles
        build.quad(
            (i * 0.25 - 5, 0.0, j * 0.25 - 5), (0.0, 0.0, 0.25), (0.25, 0.0, 0.0), (0.5,) * 3, 0
        )
    mesh = build.build().with_instance_id(int(StructureId.FLOOR))
    cut = DrawList.from_vertices(interleave_vertices(mesh))
    assert len(cut.starts) == math.ceil(3 * 3200 / draw_list.MAX_CHUNK_CORNERS)
    assert cut.counts.max() <= draw_list.MAX_CHUNK_CORNERS
    with Renderer(mesh) as split:
        a = split.render((0.0, 0.0, 0.0), 0.3, tilt=-0.5)
    monkeypatch.setattr(draw_list, "MAX_CHUNK_CORNERS", 10**9)
    with Renderer(mesh) as whole:
        b = whole.render((0.0, 0.0, 0.0), 0.3, tilt=-0.5)
    assert np.count_nonzero(a.instance_ids) > 1000
    assert np.array_equal(a.instance_ids, b.instance_ids) and np.array_equal(a.rgb, b.rgb)
