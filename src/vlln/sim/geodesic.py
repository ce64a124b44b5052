"""Geodesic distance to a goal set, computed once and then read in O(1).

habitat-lab recomputes a navmesh path query to every goal view point at every step; that
made its ObjectNav steps several times slower than PointNav. Here a :class:`GeodesicField`
runs one multi-source Dijkstra over the grid's 16-neighbour cell graph when an episode starts,
and every later distance query is a table look-up.

Edge weights are the Euclidean lengths between cell centres and an edge exists only where the
segment between the centres crosses navigable cells, so every field value is the length of a
real path on the navigable area and is never shorter than the straight line. A point inside a
cell adds its straight distance to the cell centre, which keeps that guarantee for any point.

A field may stop at a ``limit`` (metres): Dijkstra then settles only the cells within it, whose
values are exactly those of the whole field, and every other cell reads ``inf``. A goal a few
metres away (a pixel goal) costs a fraction of a whole-house field that way.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from scipy import sparse
from scipy.sparse import csgraph

from vlln.errors import NavigationError
from vlln.sim.navgrid import NavGrid, Point2

# Round-up that covers floating-point summation error along a path (< 1e-13 relative for
# paths of thousands of edges), so distances never fall below the straight line by rounding.
ROUND_UP = 1.0 + 1e-9
# A traced prefix is this much longer than asked (plus 1 m) before string pulling.
PREFIX_MARGIN = 1.2


class GeodesicField:
    """Shortest-path distance from every cell of a grid to the nearest of a set of goals.

    Goals are snapped to the nearest navigable cell centre (:meth:`NavGrid.snap_point`);
    goals outside the grid are ignored. Distances are to the snapped goals. Cells farther than
    ``limit`` metres from every goal read ``inf``, as if unreachable (module doc).
    """

    def __init__(self, grid: NavGrid, goals: Sequence[Point2], limit: float = math.inf) -> None:
        if len(goals) == 0:
            raise NavigationError("the goal set is empty; pass at least one (x, z) goal")
        rows, cols = grid.shape
        snapped: list[Point2] = []
        for x, z in goals:
            if grid.in_bounds(*grid.world_to_cell(x, z)):
                snapped.append(grid.snap_point(x, z))
        if not snapped:
            ox, oz = grid.origin
            s = grid.cell_size
            raise NavigationError(
                f"none of the {len(goals)} goals lies on the grid, which covers "
                f"x in [{ox:.2f}, {ox + cols * s:.2f}], z in [{oz:.2f}, {oz + rows * s:.2f}]; "
                "check the goals' coordinates and the grid's storey"
            )
        self.grid = grid
        self.goals: list[Point2] = list(dict.fromkeys(snapped))
        sources = sorted({_node(grid, x, z) for x, z in self.goals})
        dist, predecessors = goal_distances(grid.cell_graph(), sources, limit)
        dist.flags.writeable = False
        self.values: NDArray[np.float64] = dist.reshape(rows, cols)
        # Read by index, not as a list: a list costs more to make than most fields are read.
        self._flat = dist
        self._predecessors = predecessors
        self._ox, self._oz = grid.origin
        self._size = grid.cell_size
        self._rows, self._cols = rows, cols

    def distance(self, x: float, z: float, y: float | None = None) -> float:
        """Geodesic distance from the point to the nearest goal; ``inf`` if unreachable.

        ``y`` (the point's height) is accepted for the interface of ``StoreyField``; one
        storey does not need it.
        """
        s = self._size
        col = math.floor((x - self._ox) / s)
        row = math.floor((z - self._oz) / s)
        if not (0 <= row < self._rows and 0 <= col < self._cols):
            return math.inf
        d = float(self._flat[row * self._cols + col])
        if d == math.inf:
            return d
        cx = self._ox + (col + 0.5) * s
        cz = self._oz + (row + 0.5) * s
        return d + math.hypot(x - cx, z - cz) * ROUND_UP

    def is_reachable(self, x: float, z: float, y: float | None = None) -> bool:
        return self.distance(x, z) < math.inf

    def shortest_path(
        self, x: float, z: float, max_length: float | None = None, y: float | None = None
    ) -> list[Point2]:
        """Polyline from the point to the nearest goal along navigable cells.

        The cell path from Dijkstra is shortened by line of sight (string pulling): a corner
        is kept only where the straight segment past it would leave the navigable area. With
        ``max_length`` only a prefix at least that long is traced (the whole path when it is
        shorter), for callers that describe the first metres of a long way. ``y`` is
        accepted for the interface of ``StoreyField``.
        """
        if not self.is_reachable(x, z):
            raise NavigationError(
                f"no path from ({x:.3f}, {z:.3f}) to the goals: the point is off the "
                "navigable area or in a region the goals cannot be reached from"
            )
        node = _node(self.grid, x, z)
        chain = [node]
        predecessors = self._predecessors
        # String pulling shortens a cell chain by a few per cent: trace a safe margin more.
        limit = math.inf if max_length is None else max_length * PREFIX_MARGIN + 1.0
        cols, size, travelled = self._cols, self._size, 0.0
        while predecessors[node] >= 0 and travelled < limit:
            previous, node = node, int(predecessors[node])
            chain.append(node)
            dr, dc = node // cols - previous // cols, node % cols - previous % cols
            travelled += size * math.hypot(dr, dc)
        points = [(x, z), *(self._centre(n) for n in _turning_nodes(chain, self._cols))]
        return pull_string(self.grid, points)

    def _centre(self, node: int) -> Point2:
        return self.grid.cell_to_world(node // self._cols, node % self._cols)


def goal_distances(
    graph: sparse.csr_matrix, sources: list[int], limit: float = math.inf
) -> tuple[NDArray[np.float64], NDArray[np.int32]]:
    """One multi-source Dijkstra over a cell graph: each node's distance to the nearest source
    (rounded up, :data:`ROUND_UP`) and its next node on the way there (-9999 at a source or
    where no source can be reached). Nodes farther than ``limit`` are not settled: ``inf``."""
    dist, predecessors, _ = csgraph.dijkstra(
        graph,
        directed=True,
        indices=sources,
        min_only=True,
        return_predecessors=True,
        limit=limit,
    )
    return dist * ROUND_UP, predecessors


def _node(grid: NavGrid, x: float, z: float) -> int:
    row, col = grid.world_to_cell(x, z)
    return row * grid.shape[1] + col


def _turning_nodes(chain: list[int], cols: int) -> list[int]:
    """The chain without nodes in the middle of straight runs (same step before and after)."""
    if len(chain) <= 2:
        return chain
    kept = [chain[0]]
    for previous, node, following in zip(chain, chain[1:], chain[2:], strict=False):
        if node - previous != following - node:
            kept.append(node)
    kept.append(chain[-1])
    return kept


def pull_string(grid: NavGrid, points: list[Point2]) -> list[Point2]:
    """Drop every point that the previous kept point can see past."""
    path = [points[0]]
    for k in range(1, len(points) - 1):
        x0, z0 = path[-1]
        x1, z1 = points[k + 1]
        if not grid.segment_is_clear(x0, z0, x1, z1):
            path.append(points[k])
    if points[-1] != path[-1]:
        path.append(points[-1])
    return path
