"""One-pass rendering of RGB, depth and instance ids from a static house mesh.

The whole house is uploaded once as a single vertex buffer. Each frame is one draw call into a
framebuffer with three colour targets (RGBA8 colour, R32F depth in metres, R32I instance id)
and a depth buffer; a per-frame index list (:class:`DrawList`) skips objects outside the view
and orders the rest nearest first, which is what keeps a CPU rasteriser fast. The projection
matrix flips the image vertically, so the rows read back by OpenGL are already top-first and go
into numpy without any reordering.

Pixels where nothing was drawn have instance id 0 and depth 0 (as holes in Habitat's depth
images); surfaces farther than ``CameraSpec.max_depth`` read exactly ``max_depth``.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import TracebackType

import moderngl
import numpy as np
from numpy.typing import NDArray

from vlln.errors import ConfigError, RendererUnavailableError
from vlln.sim.camera import CameraSpec, Position
from vlln.sim.gl_context import create_headless_context, renderer_description
from vlln.sim.id_pass import InstanceIdPass
from vlln.sim.shaders import (
    FRAGMENT_SHADER,
    VERTEX_ATTRIBUTES,
    VERTEX_DTYPE,
    VERTEX_FORMAT,
    VERTEX_SHADER,
    interleave_vertices,
    pose_uniforms,
    program_uniform,
    upload_static_uniforms,
)
from vlln.world.mesh import Mesh


@dataclass
class Frame:
    """One rendered view; row 0 of every array is the top of the image."""

    rgb: NDArray[np.uint8]  # (height, width, 3) sRGB
    depth: NDArray[np.float32]  # (height, width) z-depth in metres, 0 where nothing was drawn
    instance_ids: NDArray[np.int32]  # (height, width) Mesh.instance_ids, 0 where nothing

    @staticmethod
    def allocate(spec: CameraSpec) -> Frame:
        """Uninitialised arrays of the right shapes, e.g. to reuse with ``render(out=...)``."""
        h, w = spec.height, spec.width
        return Frame(
            np.empty((h, w, 3), np.uint8),
            np.empty((h, w), np.float32),
            np.empty((h, w), np.int32),
        )


MAX_CHUNK_CORNERS = 3 * 1024  # triangle corners per culling chunk at most


@dataclass(frozen=True)
class DrawList:
    """The vertex buffer to upload, and which of its triangles to draw per frame, in what order.

    Identical vertex records (corners shared by neighbouring triangles) are stored once and
    drawn through an index list, so the vertex shader runs about half as often. The triangles
    of each instance form a contiguous chunk. Per frame, chunks whose bounding sphere misses
    the view frustum are skipped, as a CPU rasteriser would otherwise transform and clip all
    their vertices, and the rest are drawn nearest first so that hidden pixels fail the early
    depth test before shading. The structure (floor, walls, ceiling: huge triangles with no
    single meaningful distance) is drawn last. The image does not depend on the order except
    for exact depth ties.
    """

    vertices: bytes  # unique records in VERTEX_FORMAT, in order of first use
    corners: NDArray[np.uint32]  # for each triangle corner, its record in ``vertices``
    starts: NDArray[np.int64]  # first corner of each chunk
    counts: NDArray[np.int64]  # corners in each chunk
    centres: NDArray[np.float64]  # (n, 3) bounding-sphere centres
    radii: NDArray[np.float64]
    is_structure: NDArray[np.bool_]

    @staticmethod
    def from_vertices(vertex_data: bytes) -> DrawList:
        """Index a triangle soup made by :func:`interleave_vertices`."""
        records = np.frombuffer(vertex_data, VERTEX_DTYPE)
        ids = records["instance"]
        if len(ids) == 0:
            none = np.zeros(0, np.int64)
            return DrawList(
                b"", none.astype(np.uint32), none, none, np.zeros((0, 3)), np.zeros(0),
                np.zeros(0, np.bool_),
            )  # fmt: skip
        as_bytes = records.view(np.dtype((np.void, VERTEX_DTYPE.itemsize)))
        _, first_use, unique_of_corner = np.unique(as_bytes, return_index=True, return_inverse=True)
        by_first_use = np.argsort(first_use)
        rank = np.empty_like(by_first_use)
        rank[by_first_use] = np.arange(len(by_first_use))
        vertices = records[first_use[by_first_use]].tobytes()
        corners = rank[unique_of_corner.ravel()].astype(np.uint32)

        positions = records["position"].astype(np.float64)
        run_start = np.r_[True, ids[1:] != ids[:-1]]
        # Long runs (a scan's walls and floors) are cut into pieces that can be culled apart.
        run_index = np.cumsum(run_start) - 1
        corner_in_run = np.arange(len(ids)) - np.flatnonzero(run_start)[run_index]
        cut = run_start | ((corner_in_run % MAX_CHUNK_CORNERS) == 0)
        starts = np.flatnonzero(cut).astype(np.int64)
        counts = np.diff(np.r_[starts, len(ids)]).astype(np.int64)
        low = np.minimum.reduceat(positions, starts)
        high = np.maximum.reduceat(positions, starts)
        centres = (low + high) / 2.0
        offsets = np.linalg.norm(positions - np.repeat(centres, counts, axis=0), axis=1)
        radii = np.maximum.reduceat(offsets, starts)
        return DrawList(vertices, corners, starts, counts, centres, radii, ids[starts] < 0)

    def indices(
        self, spec: CameraSpec, position: Position, yaw: float, tilt: float
    ) -> NDArray[np.uint32]:
        """Indices into :attr:`vertices` to draw for this pose: visible chunks, nearest first."""
        visible, depth = spec.sphere_visibility(self.centres, self.radii, position, yaw, tilt)
        chosen = np.flatnonzero(visible)
        distance_key = np.where(self.is_structure[chosen], np.inf, depth[chosen])
        chosen = chosen[np.argsort(distance_key, kind="stable")]
        lengths = self.counts[chosen]
        # The corners start..start+length of every chosen chunk, without a Python loop.
        run_offsets = np.repeat(self.starts[chosen] - (np.cumsum(lengths) - lengths), lengths)
        return self.corners[run_offsets + np.arange(int(lengths.sum()))]


class Renderer:
    """Renders one static mesh from any camera pose; owns its own headless GL context.

    Use it as a context manager or call :meth:`close` to free the GL resources. The camera
    can be changed at any time with :meth:`set_camera` (size, field of view, depth range); the
    tilt is a per-frame argument of :meth:`render`. Several renderers may live in one process:
    each makes its own context current around every GL call.

    Back faces are culled by default, which saves rasterisation work on closed objects; pass
    ``cull_back_faces=False`` for meshes with single-sided geometry seen from behind.
    """

    def __init__(
        self, mesh: Mesh, spec: CameraSpec | None = None, *, cull_back_faces: bool = True
    ) -> None:
        self._spec = spec if spec is not None else CameraSpec()
        self._draw_list = DrawList.from_vertices(interleave_vertices(mesh))
        self._ctx = create_headless_context()
        self._framebuffer: moderngl.Framebuffer | None = None
        self._attachments: list[moderngl.Renderbuffer] = []
        self._buffers: list[moderngl.Buffer] = []
        self._vertex_array: moderngl.VertexArray | None = None
        self._id_pass: InstanceIdPass | None = None  # made on the first id-only render
        with self._ctx:
            self._ctx.enable(moderngl.DEPTH_TEST)
            if cull_back_faces:
                self._ctx.enable(moderngl.CULL_FACE)
                # The projection flips y, which turns counter-clockwise front faces clockwise.
                self._ctx.front_face = "cw"
                self._ctx.cull_face = "back"
            self._program = self._ctx.program(
                vertex_shader=VERTEX_SHADER, fragment_shader=FRAGMENT_SHADER
            )
            if self._draw_list.vertices:
                vertex_buffer = self._ctx.buffer(self._draw_list.vertices)
                self._index_buffer = self._ctx.buffer(self._draw_list.corners, dynamic=True)
                self._buffers = [vertex_buffer, self._index_buffer]
                self._vertex_array = self._ctx.vertex_array(
                    self._program,
                    [(vertex_buffer, VERTEX_FORMAT, *VERTEX_ATTRIBUTES)],
                    index_buffer=self._index_buffer,
                    index_element_size=4,
                )
        self.set_camera(self._spec)

    @property
    def spec(self) -> CameraSpec:
        return self._spec

    @property
    def description(self) -> str:
        """The OpenGL vendor, renderer and version in use (llvmpipe or a GPU)."""
        with self._ctx:
            return renderer_description(self._ctx)

    def set_camera(self, spec: CameraSpec) -> None:
        """Switch to another camera; the framebuffer is rebuilt only when the size changes."""
        size_changed = (spec.width, spec.height) != (self._spec.width, self._spec.height)
        self._spec = spec
        with self._ctx:
            if self._framebuffer is None or size_changed:
                self._release_framebuffer()
                size = (spec.width, spec.height)
                self._attachments = [
                    self._ctx.renderbuffer(size, 4, dtype="f1"),
                    self._ctx.renderbuffer(size, 1, dtype="f4"),
                    self._ctx.renderbuffer(size, 1, dtype="i4"),
                    self._ctx.depth_renderbuffer(size),
                ]
                *colors, depth = self._attachments
                self._framebuffer = self._ctx.framebuffer(colors, depth)
            upload_static_uniforms(self._program, spec)

    def render(
        self, position: Position, yaw: float, tilt: float = 0.0, out: Frame | None = None
    ) -> Frame:
        """RGB, depth and instance ids seen by an agent with its feet at ``position``.

        Fresh arrays are returned unless ``out`` (from :meth:`Frame.allocate`) is given, in
        which case it is filled in place and returned, saving the allocation per frame.
        """
        if self._framebuffer is None:
            raise RendererUnavailableError(
                "this Renderer has been closed; create a new Renderer to render again"
            )
        frame = Frame.allocate(self._spec) if out is None else self._check_out(out)
        with self._ctx:
            framebuffer = self._draw(position, yaw, tilt)
            framebuffer.read_into(frame.rgb, components=3, attachment=0)
            framebuffer.read_into(frame.depth, components=1, attachment=1, dtype="f4")
            framebuffer.read_into(frame.instance_ids, components=1, attachment=2, dtype="i4")
        return frame

    def render_instance_ids(
        self, position: Position, yaw: float, tilt: float = 0.0
    ) -> NDArray[np.int32]:
        """Only the instance-id image of :meth:`render` (what the oracle looks at), equal to
        its ``instance_ids`` pixel for pixel, drawn without any shading
        (:class:`~vlln.sim.id_pass.InstanceIdPass`)."""
        if self._framebuffer is None:
            raise RendererUnavailableError(
                "this Renderer has been closed; create a new Renderer to render again"
            )
        ids = np.empty((self._spec.height, self._spec.width), np.int32)
        if self._vertex_array is None:
            return np.zeros_like(ids)  # an empty mesh: nothing is ever drawn
        with self._ctx:
            if self._id_pass is None:
                vertex_buffer, index_buffer = self._buffers
                *_, id_attachment, depth_attachment = self._attachments
                self._id_pass = InstanceIdPass(
                    self._ctx, vertex_buffer, index_buffer, id_attachment, depth_attachment
                )
            indices = self._draw_list.indices(self._spec, position, yaw, tilt)
            if len(indices) > 0:
                self._index_buffer.write(indices)
            view_projection = pose_uniforms(self._spec, position, yaw, tilt)["u_view_projection"]
            self._id_pass.draw(view_projection, len(indices), ids)
        return ids

    def _draw(self, position: Position, yaw: float, tilt: float) -> moderngl.Framebuffer:
        """Draw the view into the framebuffer (inside the context) and return it."""
        framebuffer = self._framebuffer
        if framebuffer is None:
            raise RendererUnavailableError(
                "this Renderer has been closed; create a new Renderer to render again"
            )
        indices = self._draw_list.indices(self._spec, position, yaw, tilt)
        for name, value in pose_uniforms(self._spec, position, yaw, tilt).items():
            program_uniform(self._program, name).write(value)
        framebuffer.use()
        framebuffer.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        if self._vertex_array is not None and len(indices) > 0:
            self._index_buffer.write(indices)
            self._vertex_array.render(moderngl.TRIANGLES, vertices=len(indices))
        return framebuffer

    def close(self) -> None:
        """Free every GL resource; the renderer cannot be used afterwards."""
        if self._framebuffer is None:
            return
        with self._ctx:
            self._release_framebuffer()
            if self._vertex_array is not None:
                self._vertex_array.release()
            for buffer in self._buffers:
                buffer.release()
            self._program.release()
        self._vertex_array = None
        self._buffers = []
        self._ctx.release()

    def __enter__(self) -> Renderer:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    def _check_out(self, out: Frame) -> Frame:
        h, w = self._spec.height, self._spec.width
        wanted = {
            "rgb": (np.dtype(np.uint8), (h, w, 3)),
            "depth": (np.dtype(np.float32), (h, w)),
            "instance_ids": (np.dtype(np.int32), (h, w)),
        }
        for name, (dtype, shape) in wanted.items():
            given: NDArray[np.generic] = getattr(out, name)
            if given.shape != shape or given.dtype != dtype or not given.flags.c_contiguous:
                raise ConfigError(
                    f"out.{name} must be a C-contiguous {dtype} array of shape {shape}, got "
                    f"{given.dtype} {given.shape}; use Frame.allocate(renderer.spec)"
                )
        return out

    def _release_framebuffer(self) -> None:
        if self._id_pass is not None:  # it draws into the attachments released here
            self._id_pass.release()
            self._id_pass = None
        if self._framebuffer is not None:
            self._framebuffer.release()
        for attachment in self._attachments:
            attachment.release()
        self._attachments = []
        self._framebuffer = None
