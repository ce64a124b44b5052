"""Which triangles of a house the renderer draws for a pose, and in what order.

A CPU rasteriser pays for every triangle it is given, visible or not, so the renderer sends as
few as it can without changing the image: pieces outside the view are skipped, the rest are
drawn nearest first, and in a large scene the pieces hidden behind the nearest ones are found
on the depth image of a first pass and skipped too (:mod:`vlln.sim.occlusion`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from vlln.sim.camera import CameraSpec, Position
from vlln.sim.shaders import VERTEX_DTYPE

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
    lows: NDArray[np.float64]  # (n, 3) axis-aligned bounding-box corners, for occlusion tests
    highs: NDArray[np.float64]

    @staticmethod
    def from_vertices(vertex_data: bytes) -> DrawList:
        """Index a triangle soup made by :func:`interleave_vertices`."""
        records = np.frombuffer(vertex_data, VERTEX_DTYPE)
        ids = records["instance"]
        if len(ids) == 0:
            none = np.zeros(0, np.int64)
            return DrawList(
                b"", none.astype(np.uint32), none, none, np.zeros((0, 3)), np.zeros(0),
                np.zeros(0, np.bool_), np.zeros((0, 3)), np.zeros((0, 3)),
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
        return DrawList(
            vertices, corners, starts, counts, centres, radii, ids[starts] < 0, low, high
        )

    def visible_chunks(
        self, spec: CameraSpec, position: Position, yaw: float, tilt: float
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Chunks that may show in the view, in drawing order (nearest first, the structure
        last), and how near each one's bounding sphere comes to the eye plane."""
        visible, depth = spec.sphere_visibility(self.centres, self.radii, position, yaw, tilt)
        chosen = np.flatnonzero(visible)
        distance_key = np.where(self.is_structure[chosen], np.inf, depth[chosen])
        chosen = chosen[np.argsort(distance_key, kind="stable")]
        return chosen, depth[chosen] - self.radii[chosen]

    def corners_of(self, chunks: NDArray[np.int64]) -> NDArray[np.uint32]:
        """Indices into :attr:`vertices` of every triangle of ``chunks``, in their order."""
        lengths = self.counts[chunks]
        # The corners start..start+length of every chunk, without a Python loop.
        run_offsets = np.repeat(self.starts[chunks] - (np.cumsum(lengths) - lengths), lengths)
        return self.corners[run_offsets + np.arange(int(lengths.sum()))]

    def indices(
        self, spec: CameraSpec, position: Position, yaw: float, tilt: float
    ) -> NDArray[np.uint32]:
        """Indices into :attr:`vertices` to draw for this pose: visible chunks, nearest first."""
        return self.corners_of(self.visible_chunks(spec, position, yaw, tilt)[0])

    def nearest(
        self, chunks: NDArray[np.int64], nearness: NDArray[np.float64], budget: int
    ) -> NDArray[np.bool_]:
        """Which of ``chunks`` are the nearest ones, up to ``budget`` triangles (at least one)."""
        by_nearness = np.argsort(nearness, kind="stable")
        triangles = np.cumsum(self.counts[chunks][by_nearness]) // 3
        near = np.zeros(len(chunks), np.bool_)
        near[by_nearness[: max(1, int(np.searchsorted(triangles, budget, side="right")))]] = True
        return near
