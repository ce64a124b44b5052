"""`vlln bench sim`: how fast the simulator renders, steps and answers distance queries.

``raw_raster_fps`` draws the same triangles with the same shaders and reads back the same
three images in a bare moderngl loop with precomputed uniforms: the physical limit of this
machine's rasteriser, against which ``render_fps`` and ``step_fps`` show the simulator's own
overhead. ``render_cpu_ms`` (CPU time per rendered frame, the rasteriser's threads included)
and ``drawn_triangles`` (triangles left after culling, per frame) change little with the
machine's load, so they compare runs taken in busy and quiet minutes.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import moderngl
import numpy as np

from vlln.bench.figures import Figure, emit, median_seconds
from vlln.bench.parallel import run_parallel_benchmark
from vlln.bench.settings import SimBench
from vlln.bench.walks import goal_sets, random_point, random_walk, step_fps
from vlln.sim.agent import AgentState
from vlln.sim.camera import CameraSpec
from vlln.sim.draw_list import DrawList
from vlln.sim.geodesic import GeodesicField
from vlln.sim.gl_context import create_headless_context
from vlln.sim.shaders import (
    FRAGMENT_SHADER,
    VERTEX_ATTRIBUTES,
    VERTEX_FORMAT,
    VERTEX_SHADER,
    interleave_vertices,
    pose_uniforms,
    program_uniform,
    upload_static_uniforms,
)
from vlln.sim.simulator import Simulator
from vlln.sim.storey_field import StoreyField
from vlln.sim.viewpoints import GoalPoint
from vlln.world.generator import generate_house
from vlln.world.mesh import Mesh
from vlln.world.model import House
from vlln.world.scans import ImportReport, export_scene, import_scene, with_subdivided_mesh

# Frames drawn before any clock starts: shader compilation, first allocations, caches.
WARM_UP_FRAMES = 30


def run_sim_benchmark(settings: SimBench) -> list[Figure]:
    """Measure and print every simulator figure for house ``seed``, or for the scanned scene
    folder ``scene``, or for house ``seed`` exported as a scan with every triangle split into
    ``4**subdivide`` (then the import time and the simulator's build time instead of the
    house build time, and no memory probe); with ``envs``, the parallel figures instead
    (:mod:`vlln.bench.parallel`).

    The three frame rates replay the same walk ``repeats`` times, interleaved, and report the
    median pass, so a neighbour's burst on a shared machine moves all three alike.
    """
    if settings.envs is not None:
        return run_parallel_benchmark(settings, settings.envs)
    seed, frames, repeats, as_json = (
        settings.seed,
        settings.frames,
        settings.repeats,
        settings.as_json,
    )
    scene, subdivide = settings.scene, settings.subdivide
    figures: list[Figure] = []

    def record(metric: str, value: float, unit: str) -> None:
        figure = Figure(metric, value, unit)
        figures.append(figure)
        emit(figure, as_json)

    imported = scene is not None or subdivide > 0
    if not imported:
        build_s = median_seconds(lambda: generate_house(seed), repeats=3)
        record("house_build_s", build_s, "s")
        house = generate_house(seed)
    else:
        house, report = _import(scene, seed, subdivide)
        record("scene_import_s", report.seconds, "s")
    record("house_triangles", house.geometry.mesh.n_triangles if house.geometry else 0, "count")
    rng = np.random.default_rng(seed)
    started = time.perf_counter()
    with Simulator(house) as sim:
        if imported:
            record("simulator_build_s", time.perf_counter() - started, "s")
        walk = random_walk(sim, rng, frames)
        goals = goal_sets(sim, rng, count=3)
        drawn = _drawn_corners(sim, walk.poses)
        passes: dict[str, list[float]] = {
            "render_fps": [],
            "render_cpu_ms": [],
            "raw_raster_fps": [],
            "step_fps": [],
        }
        for _ in range(repeats):
            fps, cpu_ms = _render_fps(sim, walk.poses)
            passes["render_fps"].append(fps)
            passes["render_cpu_ms"].append(cpu_ms)
            passes["raw_raster_fps"].append(_raw_raster_fps(sim, walk.poses, drawn))
            passes["step_fps"].append(step_fps(sim, walk, goals[2]))
        for metric in ("render_fps", "raw_raster_fps"):
            record(metric, statistics.median(passes[metric]), "frames/s")
        record("render_cpu_ms", statistics.median(passes["render_cpu_ms"]), "ms/frame")
        record("drawn_triangles", sum(len(c) for c in drawn) / 12 / len(drawn), "count/frame")
        record("step_fps", statistics.median(passes["step_fps"]), "steps/s")
        field_s = median_seconds(lambda: _fresh_field(sim, goals[0]), repeats=5)
        record("field_build_ms", field_s * 1e3, "ms")
        record("geodesic_query_us", _query_us(sim, _fresh_field(sim, goals[1]), rng), "us")
    if not imported:
        record("sim_rss_mb", _rss_of_fresh_simulator(seed), "MiB")
    return figures


def _import(scene: Path | None, seed: int, subdivide: int) -> tuple[House, ImportReport]:
    """The scanned scene ``scene``, or house ``seed`` written as a subdivided Matterport3D
    scan into a temporary folder and imported back."""
    if scene is not None:
        return import_scene(scene)
    house = with_subdivided_mesh(generate_house(seed), subdivide)
    with tempfile.TemporaryDirectory(prefix="vlln-scan-") as folder:
        return import_scene(export_scene(house, Path(folder), "mp3d"))


def _render_fps(sim: Simulator, poses: list[AgentState]) -> tuple[float, float]:
    """Frames per second, and CPU milliseconds per frame of the whole process (the
    rasteriser's threads included): a figure that a busy machine does not inflate much."""
    for pose in poses[:WARM_UP_FRAMES]:  # llvmpipe compiles shader variants lazily
        sim.render(pose)
    cpu_start = time.process_time()
    start = time.perf_counter()
    for pose in poses:
        sim.render(pose)
    seconds = time.perf_counter() - start
    return len(poses) / seconds, (time.process_time() - cpu_start) / len(poses) * 1e3


def _drawn_corners(sim: Simulator, poses: list[AgentState]) -> list[bytes]:
    """The vertex indices the renderer draws for each pose, after culling."""
    drawn = []
    for p in poses:
        sim.renderer.render(p.position, p.yaw, p.tilt)
        drawn.append(sim.renderer.last_drawn_corners().tobytes())
    return drawn


def _raw_raster_fps(sim: Simulator, poses: list[AgentState], drawn: list[bytes]) -> float:
    """The renderer's per-frame GL work (uniforms, index list, one draw, three read-backs)
    with every index list and uniform prepared before the clock starts: the triangles the
    renderer drew for each pose after culling (``drawn``), in one pass."""
    assert sim.house.geometry is not None  # a Simulator refuses houses without geometry
    mesh: Mesh = sim.house.geometry.mesh
    spec: CameraSpec = sim.config.camera
    draw_list = DrawList.from_vertices(interleave_vertices(mesh))
    ctx = create_headless_context()
    try:
        with ctx:
            ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
            ctx.front_face = "cw"
            program = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=FRAGMENT_SHADER)
            upload_static_uniforms(program, spec)
            vbo = ctx.buffer(draw_list.vertices)
            ibo = ctx.buffer(draw_list.corners, dynamic=True)
            vao = ctx.vertex_array(
                program,
                [(vbo, VERTEX_FORMAT, *VERTEX_ATTRIBUTES)],
                index_buffer=ibo,
                index_element_size=4,
            )
            size = (spec.width, spec.height)
            targets = [
                ctx.renderbuffer(size, 4, dtype="f1"),
                ctx.renderbuffer(size, 1, dtype="f4"),
                ctx.renderbuffer(size, 1, dtype="i4"),
            ]
            fbo = ctx.framebuffer(targets, ctx.depth_renderbuffer(size))
            rgb = np.empty((spec.height, spec.width, 3), np.uint8)
            depth = np.empty((spec.height, spec.width), np.float32)
            ids = np.empty((spec.height, spec.width), np.int32)
            frames = []
            for p, indices in zip(poses, drawn, strict=True):
                uniforms = pose_uniforms(spec, p.position, p.yaw, p.tilt).items()
                frames.append(([(program_uniform(program, n), v) for n, v in uniforms], indices))

            def draw(uniforms: list[tuple[moderngl.Uniform, bytes]], indices: bytes) -> None:
                for uniform, value in uniforms:
                    uniform.write(value)
                ibo.write(indices)
                fbo.use()
                fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
                vao.render(moderngl.TRIANGLES, vertices=len(indices) // 4)
                fbo.read_into(rgb, components=3, attachment=0)
                fbo.read_into(depth, components=1, attachment=1, dtype="f4")
                fbo.read_into(ids, components=1, attachment=2, dtype="i4")

            for frame in frames[:WARM_UP_FRAMES]:
                draw(*frame)
            start = time.perf_counter()
            for frame in frames:
                draw(*frame)
            return len(frames) / (time.perf_counter() - start)
    finally:
        ctx.release()


def _fresh_field(sim: Simulator, goals: list[GoalPoint]) -> GeodesicField | StoreyField:
    """A distance field built now (the simulator's own are cached)."""
    if sim.storeys is not None:
        return StoreyField(sim.storeys, goals)
    return GeodesicField(sim.grid, [(goal[0], goal[-1]) for goal in goals])


def _query_us(
    sim: Simulator, field: GeodesicField | StoreyField, rng: np.random.Generator
) -> float:
    points = [random_point(sim, rng) for _ in range(2000)] * 50
    distance = field.distance
    start = time.perf_counter()
    if sim.storeys is None:  # a one-storey query needs no height
        for x, _, z in points:
            distance(x, z)
    else:
        for x, y, z in points:
            distance(x, z, y)
    return (time.perf_counter() - start) / len(points) * 1e6


_RSS_PROBE = """
import gc, json, sys
from vlln.sim.simulator import Simulator
from vlln.world.generator import generate_house
sim = Simulator(generate_house(int(sys.argv[1])))
sim.render()
gc.collect()
for line in open("/proc/self/status"):
    if line.startswith("VmRSS:"):
        print(json.dumps(int(line.split()[1]) / 1024))
"""


def _rss_of_fresh_simulator(seed: int) -> float:
    """Resident memory of a process holding one live simulator (interpreter included)."""
    result = subprocess.run(
        [sys.executable, "-c", _RSS_PROBE, str(seed)],
        capture_output=True,
        text=True,
        check=True,
    )
    return float(json.loads(result.stdout.strip().splitlines()[-1]))
