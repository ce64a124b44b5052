"""The navigable area of a house with several storeys, joined by flights of stairs.

Each storey keeps its own :class:`~vlln.sim.navgrid.NavGrid` on one cell lattice shared by
all storeys. A flight's treads are walkable on both storeys it joins (see
``NavGrid.from_mesh(ramp_ids=...)``); its shaft walls let it be entered only from its foot
below and its head above. A cell of a flight is therefore in two grids at the same height,
and that shared cell is where the storeys meet: the graph over all storeys joins the two
copies, so one Dijkstra finds paths that climb or descend. A flight reaches a storey when its
foot is on that floor or its top tread is level with it, or when its first rise steps up from
the floor or its last rise steps onto it (ordinary stairs, whose top landing is the floor
itself; :func:`vlln.world.model.top_at`).

Heights: every cell of a storey has a walking height, the floor's except on a flight,
where it is the top of the tread under the cell centre. The agent belongs to the storey
whose floor is nearest its height, so halfway up a flight it passes to the storey above.
Edges on a flight are as long as the slope makes them (plan length times
``sqrt(1 + slope^2)``), so no path is shorter than the straight line in 3-D.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray
from scipy import sparse
from scipy.sparse import csgraph

from vlln.errors import ConfigError, NavigationError
from vlln.sim.footprint import floor_cells
from vlln.sim.navgrid import NavGrid, lattice_extent
from vlln.world.mesh import Mesh
from vlln.world.model import StructureId, foot_on, nearest_floor, top_at

Point3 = tuple[float, float, float]

# Weight of the edge between the two copies of a flight's cell (one place, two storeys).
_SAME_PLACE = 1e-9


class Storeys:
    """Per-storey grids on one lattice, their walking heights, and the graph across them."""

    def __init__(
        self,
        grids: Sequence[NavGrid],
        heights: Sequence[NDArray[np.float64]],
        slopes: Sequence[NDArray[np.float64]],
    ) -> None:
        if len(grids) < 2:
            raise ConfigError("Storeys joins two or more storeys; use a NavGrid for one")
        first = grids[0]
        for grid in grids:
            if grid.shape != first.shape or grid.origin != first.origin:
                raise ConfigError("every storey's grid must share one cell lattice")
        self.grids: tuple[NavGrid, ...] = tuple(grids)
        self.heights = tuple(np.asarray(h, np.float64) for h in heights)
        self._slopes = tuple(np.asarray(s, np.float64) for s in slopes)
        self.floor_ys = tuple(grid.floor_y for grid in grids)
        self.cell_size = first.cell_size
        self.origin = first.origin
        self.shape = first.shape
        self._cells = first.shape[0] * first.shape[1]
        self._graph: sparse.csr_matrix | None = None
        self._labels: tuple[NDArray[np.int32], int] | None = None

    @staticmethod
    def from_mesh(
        mesh: Mesh,
        floor_ys: Sequence[float],
        ramp_ids: Sequence[int],
        cell_size: float = 0.05,
        agent_radius: float = 0.18,
        agent_height: float = 1.5,
        step_height: float = 0.15,
    ) -> Storeys:
        """The storeys whose floors are at ``floor_ys`` (ascending), joined by the flights whose
        instance ids are ``ramp_ids``."""
        triangles = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
        ids = mesh.instance_ids[::3].astype(np.int64)
        walkable = np.isin(ids, [int(StructureId.FLOOR), *ramp_ids])
        if not walkable.any():
            raise NavigationError("the mesh has no floor triangles to walk on")
        extent = lattice_extent(triangles[walkable], cell_size)
        spans = {r: _span(triangles[ids == r]) for r in ramp_ids}
        grids, heights, slopes = [], [], []
        for level, floor_y in enumerate(floor_ys):
            reaching = [r for r, (low, high, _) in spans.items() if _meets(floor_y, low, high)]
            grid = NavGrid.from_mesh(
                mesh,
                floor_y=floor_y,
                cell_size=cell_size,
                agent_radius=agent_radius,
                agent_height=agent_height,
                step_height=step_height,
                level=level,
                ramp_ids=frozenset(reaching),
                extent=extent,
            )
            height = np.full(grid.shape, floor_y, np.float64)
            slope = np.zeros(grid.shape, np.float64)
            for r in reaching:
                _paint_treads(triangles[ids == r], extent, cell_size, height, slope, spans[r][2])
            grids.append(grid)
            heights.append(height)
            slopes.append(slope)
        return Storeys(grids, heights, slopes)

    # ------------------------------------------------------------------ points

    def level_of(self, y: float) -> int:
        """The storey whose floor is nearest the height (the lower one on a tie)."""
        return nearest_floor(self.floor_ys, y)

    def level_under(self, y: float) -> int:
        """The highest storey whose floor is at or below the height: where an object whose
        bottom is at ``y`` stands (a lamp under a ceiling belongs to the storey below it)."""
        return max(k for k, floor in enumerate(self.floor_ys) if floor <= y + 0.05 or k == 0)

    def grid_at(self, y: float) -> NavGrid:
        return self.grids[self.level_of(y)]

    def height_at(self, level: int, x: float, z: float) -> float:
        """Walking height of storey ``level`` at the point (its floor off the grid)."""
        row, col = self.grids[level].world_to_cell(x, z)
        if self.grids[level].in_bounds(row, col):
            return float(self.heights[level][row, col])
        return self.floor_ys[level]

    def is_navigable(self, x: float, y: float, z: float) -> bool:
        return self.grid_at(y).is_navigable(x, z)

    def node(self, x: float, y: float, z: float) -> int:
        """Graph node of the point's cell on its storey."""
        level = self.level_of(y)
        row, col = self.grids[level].world_to_cell(x, z)
        return level * self._cells + row * self.shape[1] + col

    def node_point(self, node: int) -> Point3:
        """``(x, y, z)`` of a node's cell centre at its walking height."""
        level, flat = divmod(int(node), self._cells)
        row, col = divmod(flat, self.shape[1])
        x, z = self.grids[level].cell_to_world(row, col)
        return x, float(self.heights[level][row, col]), z

    def snap_point(self, x: float, y: float, z: float) -> Point3:
        """The nearest navigable cell centre on the point's storey, at its walking height."""
        level = self.level_of(y)
        sx, sz = self.grids[level].snap_point(x, z)
        return sx, self.height_at(level, sx, sz), sz

    # ----------------------------------------------------------------- graph

    def cell_graph(self) -> sparse.csr_matrix:
        """One graph over every storey's cells (node = ``level * rows * cols + cell``): each
        storey's 16-neighbour graph, edges on flights lengthened by their slope, and an edge
        between the two copies of every flight cell."""
        if self._graph is None:
            rows, cols, weights = [], [], []
            for level, (grid, slope) in enumerate(zip(self.grids, self._slopes, strict=True)):
                graph = grid.cell_graph().tocoo()
                steep = np.maximum(slope.ravel()[graph.row], slope.ravel()[graph.col])
                offset = level * self._cells
                rows += [graph.row + offset]
                cols += [graph.col + offset]
                weights += [graph.data * np.sqrt(1.0 + steep**2)]
            for level in range(len(self.grids) - 1):
                shared = (
                    self.grids[level].navigable
                    & self.grids[level + 1].navigable
                    & (self.heights[level] == self.heights[level + 1])
                ).ravel()
                below = np.flatnonzero(shared) + level * self._cells
                above = below + self._cells
                rows += [below, above]
                cols += [above, below]
                weights += [np.full(2 * below.size, _SAME_PLACE)]
            size = len(self.grids) * self._cells
            self._graph = sparse.csr_matrix(
                (np.concatenate(weights), (np.concatenate(rows), np.concatenate(cols))),
                shape=(size, size),
            )
        return self._graph

    def components(self) -> tuple[NDArray[np.int32], int]:
        """Component label (1..n) of every node; 0 for cells that are not navigable."""
        if self._labels is None:
            count, labels = csgraph.connected_components(self.cell_graph(), directed=False)
            navigable = np.concatenate([g.navigable.ravel() for g in self.grids])
            # Renumber so that navigable components are 1..n and the rest 0.
            used = np.unique(labels[navigable])
            lookup = np.zeros(count, np.int32)
            lookup[used] = np.arange(1, used.size + 1, dtype=np.int32)
            marked = np.where(navigable, lookup[labels], 0).astype(np.int32)
            self._labels = (marked, int(used.size))
        return self._labels

    def largest_component(self) -> int:
        labels, count = self.components()
        if count == 0:
            raise NavigationError("the storeys have no navigable cells")
        return int(np.argmax(np.bincount(labels, minlength=count + 1)[1:]) + 1)

    def sample_navigable_point(self, rng: np.random.Generator, component: int) -> Point3:
        """Centre of a uniformly drawn navigable cell of one component, any storey."""
        flat = np.flatnonzero(self.components()[0] == component)
        if flat.size == 0:
            raise NavigationError(f"component {component} has no navigable cells")
        return self.node_point(int(flat[int(rng.integers(flat.size))]))

    @property
    def navigable_area(self) -> float:
        return sum(grid.navigable_area for grid in self.grids)


def _span(triangles: NDArray[np.float64]) -> tuple[float, float, float]:
    """Lowest and highest point of a flight, and its slope (rise over the longer plan side)."""
    low, high = float(triangles[:, :, 1].min()), float(triangles[:, :, 1].max())
    plan = triangles[:, :, [0, 2]].reshape(-1, 2)
    run = float(np.max(plan.max(axis=0) - plan.min(axis=0)))
    return low, high, (high - low) / run if run > 0.0 else 0.0


def _meets(floor_y: float, low: float, high: float) -> bool:
    return foot_on(floor_y, low) or top_at(floor_y, high)


def _paint_treads(
    triangles: NDArray[np.float64],
    extent: tuple[tuple[float, float], tuple[int, int]],
    cell_size: float,
    height: NDArray[np.float64],
    slope: NDArray[np.float64],
    flight_slope: float,
) -> None:
    """Write each tread's height (and the flight's slope) into the cells it covers."""
    heights = triangles[:, :, 1]
    flat = np.ptp(heights, axis=1) == 0.0
    origin, shape = extent
    for y in np.unique(heights[flat, 0]):
        covered = floor_cells(triangles[flat & (heights[:, 0] == y)], origin, cell_size, shape)
        height[covered] = y
        slope[covered] = flight_slope
