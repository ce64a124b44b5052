"""The navigable area of one storey as a grid of square cells.

A cell is navigable when it lies on this storey's floor and an upright cylinder of the agent's
radius and height standing on its centre touches no other geometry. The grid is derived from
the house mesh alone (see :meth:`NavGrid.from_mesh`), so a generated house needs no separate
navigation data.

Indexing: ``navigable[row, col]``; rows run along +z, columns along +x; cell ``(row, col)``
covers ``x in [ox + col * s, ox + (col + 1) * s)`` and ``z in [oz + row * s, oz + (row + 1) * s)``
for ``origin = (ox, oz)`` and cell size ``s``. The continuous navigable region is the union of
navigable cells; motion and line-of-sight checks walk every cell a segment crosses.

A grid knows its storey (``level``, ``floor_y``). Everything that measures distances works on a
grid and cell indices; :mod:`vlln.sim.storeys` joins the grids of several storeys through the
cells of their stairs.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage, sparse

from vlln.errors import ConfigError, NavigationError
from vlln.sim.footprint import floor_cells, obstacle_cells
from vlln.world.mesh import Mesh
from vlln.world.model import StructureId

Point2 = tuple[float, float]
Cell = tuple[int, int]

# Offsets (drow, dcol) of half of the 16-neighbourhood; the other half are their negatives.
# Each lists the intermediate cells a straight segment between the two centres crosses.
_NEIGHBOURS: tuple[tuple[int, int, tuple[Cell, ...]], ...] = (
    (0, 1, ()),
    (1, 0, ()),
    (1, 1, ((0, 1), (1, 0))),
    (1, -1, ((0, -1), (1, 0))),
    (1, 2, ((0, 1), (1, 1))),
    (2, 1, ((1, 0), (1, 1))),
    (1, -2, ((0, -1), (1, -1))),
    (2, -1, ((1, 0), (1, -1))),
)

# A stop point on the boundary of a blocked cell is moved this far (in cells) back inside the
# last free cell, so rounding can never place the agent on a blocked cell.
_INSET = 1e-6


class Cast(NamedTuple):
    """How far a straight move got: its stop point, the fraction of the move done, and the
    axis of the blocking cell boundary (0: constant x, 1: constant z, -1: not blocked)."""

    x: float
    z: float
    fraction: float
    axis: int


class NavGrid:
    """Navigable cells of one storey, with O(1) point queries and segment casting."""

    def __init__(
        self,
        navigable: NDArray[np.bool_],
        origin: Point2,
        cell_size: float,
        level: int = 0,
        floor_y: float = 0.0,
    ) -> None:
        if navigable.ndim != 2 or navigable.size == 0:
            raise ConfigError(f"navigable must be a non-empty 2-D array, got {navigable.shape}")
        if not cell_size > 0.0:
            raise ConfigError(f"cell_size must be positive, got {cell_size}")
        self.navigable: NDArray[np.bool_] = np.array(navigable, dtype=bool, order="C")
        self.navigable.flags.writeable = False
        self.origin: Point2 = (float(origin[0]), float(origin[1]))
        self.cell_size = float(cell_size)
        self.level = int(level)
        self.floor_y = float(floor_y)
        self._rows, self._cols = self.navigable.shape
        # Python-level copies make single-point queries cheap (no numpy scalar overhead).
        self._free = self.navigable.tobytes()
        self._labels: tuple[NDArray[np.int32], int] | None = None
        self._nearest: NDArray[np.intp] | None = None
        self._graph: sparse.csr_matrix | None = None

    @staticmethod
    def from_mesh(
        mesh: Mesh,
        floor_y: float = 0.0,
        cell_size: float = 0.05,
        agent_radius: float = 0.18,
        agent_height: float = 1.5,
        step_height: float = 0.15,
        level: int = 0,
        ramp_ids: frozenset[int] = frozenset(),
        extent: tuple[Point2, tuple[int, int]] | None = None,
    ) -> NavGrid:
        """Rasterise the storey whose floor is at ``floor_y``.

        Walkable: cells whose centre lies on a floor triangle (``StructureId.FLOOR``) within
        ``step_height`` of ``floor_y``. Blocked: cells whose column meets any other triangle
        in the height band ``(floor_y + step_height, floor_y + agent_height]`` (walls count:
        the test is exact for vertical faces), plus cells enclosed by one object's footprint
        (the inside of a closed wardrobe is not floor). Free cells within ``agent_radius``
        (centre to centre) of a blocked or non-floor cell are dropped.

        The horizontal faces of the instances in ``ramp_ids`` (flights of stairs that reach
        this storey) are walkable at any height and never block. ``extent`` (origin, shape)
        fixes the cell lattice, so that the storeys of one house share it.
        """
        if not cell_size > 0.0:
            raise ConfigError(f"cell_size must be positive, got {cell_size}")
        if not agent_radius >= 0.0:
            raise ConfigError(f"agent_radius must be >= 0, got {agent_radius}")
        if not 0.0 <= step_height < agent_height:
            raise ConfigError(
                f"need 0 <= step_height < agent_height, got step_height={step_height}, "
                f"agent_height={agent_height}"
            )
        triangles = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
        ids = mesh.instance_ids[::3].astype(np.int64)
        heights = triangles[:, :, 1]
        on_level = np.all(np.abs(heights - floor_y) <= step_height, axis=1)
        is_floor = (ids == StructureId.FLOOR) & on_level
        is_ramp = np.isin(ids, list(ramp_ids)) if ramp_ids else np.zeros(len(ids), bool)
        if ramp_ids:
            is_floor |= is_ramp & (np.ptp(heights, axis=1) == 0.0)
        if not is_floor.any():
            raise NavigationError(
                f"the mesh has no floor triangles (instance id {int(StructureId.FLOOR)}) "
                f"within {step_height} m of floor_y={floor_y}; check floor_y"
            )
        if extent is None:
            extent = lattice_extent(triangles[is_floor], cell_size)
        origin, shape = extent

        floor = floor_cells(triangles[is_floor], origin, cell_size, shape)
        band = (floor_y + step_height, floor_y + agent_height)
        others = ~is_floor & ~is_ramp
        blocked = obstacle_cells(triangles[others], ids[others], band, origin, cell_size, shape)
        free = floor & ~blocked
        clearance = ndimage.distance_transform_edt(free, sampling=cell_size)
        navigable = free & (clearance > agent_radius)
        return NavGrid(navigable, origin, cell_size, level=level, floor_y=floor_y)

    # ----------------------------------------------------------------- geometry of cells

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``: cells along z, cells along x."""
        return self._rows, self._cols

    @property
    def navigable_area(self) -> float:
        """Navigable area in square metres."""
        return float(np.count_nonzero(self.navigable)) * self.cell_size**2

    def world_to_cell(self, x: float, z: float) -> Cell:
        """``(row, col)`` of the cell containing the point; may lie outside the grid."""
        s = self.cell_size
        return math.floor((z - self.origin[1]) / s), math.floor((x - self.origin[0]) / s)

    def cell_to_world(self, row: int, col: int) -> Point2:
        """Floor-plan centre ``(x, z)`` of a cell."""
        s = self.cell_size
        return self.origin[0] + (col + 0.5) * s, self.origin[1] + (row + 0.5) * s

    def in_bounds(self, row: int, col: int) -> bool:
        return 0 <= row < self._rows and 0 <= col < self._cols

    def is_free_cell(self, row: int, col: int) -> bool:
        """Whether a cell is navigable; cells outside the grid are not."""
        if 0 <= row < self._rows and 0 <= col < self._cols:
            return self._free[row * self._cols + col] != 0
        return False

    def is_navigable(self, x: float, z: float) -> bool:
        row, col = self.world_to_cell(x, z)
        return self.is_free_cell(row, col)

    def free_cells(self) -> NDArray[np.intp]:
        """``(n, 2)`` array of navigable ``(row, col)``, in row-major order."""
        return np.argwhere(self.navigable)

    def snap_point(self, x: float, z: float) -> Point2:
        """Centre of the navigable cell nearest to the point's cell (its own when navigable).

        Points outside the grid are first moved to the nearest cell on its border.
        """
        row, col = self.world_to_cell(x, z)
        row = min(max(row, 0), self._rows - 1)
        col = min(max(col, 0), self._cols - 1)
        if self._free[row * self._cols + col]:
            return self.cell_to_world(row, col)
        nearest = self._nearest_free_index()
        target = int(nearest[row, col])
        return self.cell_to_world(target // self._cols, target % self._cols)

    def _nearest_free_index(self) -> NDArray[np.intp]:
        if self._nearest is None:
            if not self.navigable.any():
                raise NavigationError("the grid has no navigable cell to snap to")
            _, (rows, cols) = ndimage.distance_transform_edt(~self.navigable, return_indices=True)
            self._nearest = rows * self._cols + cols
        return self._nearest

    # ------------------------------------------------------------------ connectivity

    def components(self) -> tuple[NDArray[np.int32], int]:
        """Labels of 8-connected navigable regions (0 = not navigable) and their count."""
        if self._labels is None:
            labels, count = ndimage.label(self.navigable, structure=np.ones((3, 3), bool))
            self._labels = (labels.astype(np.int32), int(count))
        return self._labels

    def component_of(self, x: float, z: float) -> int:
        """Component label of the point, 0 when it is not navigable."""
        row, col = self.world_to_cell(x, z)
        if not self.in_bounds(row, col):
            return 0
        return int(self.components()[0][row, col])

    def largest_component(self) -> int:
        """Label of the component with the most cells."""
        labels, count = self.components()
        if count == 0:
            raise NavigationError("the grid has no navigable cells")
        sizes = np.bincount(labels.ravel(), minlength=count + 1)
        return int(np.argmax(sizes[1:]) + 1)

    def sample_navigable_point(
        self, rng: np.random.Generator, component: int | None = None
    ) -> Point2:
        """Centre of a uniformly drawn navigable cell, optionally within one component."""
        if component is None:
            mask = self.navigable
        else:
            labels, count = self.components()
            if not 1 <= component <= count:
                raise ConfigError(f"component must be in 1..{count}, got {component}")
            mask = labels == component
        flat = np.flatnonzero(mask)
        if flat.size == 0:
            raise NavigationError("the grid has no navigable cells to sample from")
        index = int(flat[int(rng.integers(flat.size))])
        return self.cell_to_world(index // self._cols, index % self._cols)

    # ------------------------------------------------------------- segments and graph

    def cast(self, x: float, z: float, dx: float, dz: float) -> Cast:
        """Walk the segment ``(x, z) -> (x + dx, z + dz)`` through every cell it crosses.

        The move stops just before the first blocked cell; the stop point always lies inside a
        navigable cell. The start must be navigable.
        """
        s = self.cell_size
        fx = (x - self.origin[0]) / s
        fz = (z - self.origin[1]) / s
        col = math.floor(fx)
        row = math.floor(fz)
        free, cols, rows = self._free, self._cols, self._rows
        if not (0 <= row < rows and 0 <= col < cols and free[row * cols + col]):
            raise NavigationError(
                f"a move starts off the navigable area at ({x:.3f}, {z:.3f}); "
                "place the agent with NavGrid.snap_point"
            )
        inf = math.inf
        step_c = 1 if dx > 0.0 else -1
        step_r = 1 if dz > 0.0 else -1
        # Fraction of the move at which the next column / row boundary is crossed.
        t_col = ((col + (dx > 0.0)) - fx) * s / dx if dx != 0.0 else inf
        t_row = ((row + (dz > 0.0)) - fz) * s / dz if dz != 0.0 else inf
        dt_col = s / abs(dx) if dx != 0.0 else inf
        dt_row = s / abs(dz) if dz != 0.0 else inf
        t, axis = 1.0, -1
        while True:
            if t_col <= t_row:
                if t_col >= 1.0:
                    break
                c = col + step_c
                if not (0 <= c < cols and free[row * cols + c]):
                    t, axis = t_col, 0
                    break
                col = c
                t_col += dt_col
            else:
                if t_row >= 1.0:
                    break
                r = row + step_r
                if not (0 <= r < rows and free[r * cols + col]):
                    t, axis = t_row, 1
                    break
                row = r
                t_row += dt_row
        px, pz = x + dx * t, z + dz * t
        end_col = math.floor((px - self.origin[0]) / s)
        end_row = math.floor((pz - self.origin[1]) / s)
        if (end_row, end_col) != (row, col) and not self.is_free_cell(end_row, end_col):
            # On the boundary of a blocked cell (or past it by rounding): step back inside.
            lo_x = self.origin[0] + col * s
            lo_z = self.origin[1] + row * s
            inset = _INSET * s
            px = min(max(px, lo_x + inset), lo_x + s - inset)
            pz = min(max(pz, lo_z + inset), lo_z + s - inset)
        return Cast(px, pz, t, axis)

    def segment_is_clear(self, x0: float, z0: float, x1: float, z1: float) -> bool:
        """Whether every cell the segment crosses is navigable."""
        if not self.is_navigable(x0, z0):
            return False
        return self.cast(x0, z0, x1 - x0, z1 - z0).axis < 0

    def cell_graph(self) -> sparse.csr_matrix:
        """Symmetric 16-neighbour graph over all cells (node = ``row * cols + col``).

        Two navigable cells are joined when the straight segment between their centres
        crosses navigable cells only; the weight is its length in metres. Built once, cached.
        """
        if self._graph is None:
            self._graph = _build_cell_graph(self.navigable, self.cell_size)
        return self._graph


def lattice_extent(
    floor_triangles: NDArray[np.float64], cell_size: float
) -> tuple[Point2, tuple[int, int]]:
    """Origin and ``(rows, cols)`` of a cell lattice covering the triangles, one cell spare."""
    floor_xz = floor_triangles[:, :, [0, 2]].reshape(-1, 2)
    low = np.floor(floor_xz.min(axis=0) / cell_size) - 1.0
    high = np.ceil(floor_xz.max(axis=0) / cell_size) + 1.0
    origin = (float(low[0] * cell_size), float(low[1] * cell_size))
    return origin, (int(high[1] - low[1]), int(high[0] - low[0]))


def _build_cell_graph(navigable: NDArray[np.bool_], cell_size: float) -> sparse.csr_matrix:
    rows, cols = navigable.shape
    pad = 2
    padded = np.zeros((rows + 2 * pad, cols + 2 * pad), bool)
    padded[pad:-pad, pad:-pad] = navigable
    node = np.arange(rows * cols, dtype=np.int32).reshape(rows, cols)

    def shifted(dr: int, dc: int) -> NDArray[np.bool_]:
        return padded[pad + dr : pad + dr + rows, pad + dc : pad + dc + cols]

    sources: list[NDArray[np.int32]] = []
    targets: list[NDArray[np.int32]] = []
    weights: list[NDArray[np.float64]] = []
    for dr, dc, between in _NEIGHBOURS:
        ok = navigable & shifted(dr, dc)
        for br, bc in between:
            ok &= shifted(br, bc)
        a = node[ok]
        b = a + np.int32(dr * cols + dc)
        length = cell_size * math.hypot(dr, dc)
        sources += [a, b]
        targets += [b, a]
        weights.append(np.full(2 * a.size, length))
    src = np.concatenate(sources)
    dst = np.concatenate(targets)
    order = np.argsort(src, kind="stable")
    indptr = np.zeros(rows * cols + 1, np.int64)
    np.cumsum(np.bincount(src, minlength=rows * cols), out=indptr[1:])
    data = np.concatenate(weights)[order]
    return sparse.csr_matrix((data, dst[order], indptr), shape=(rows * cols, rows * cols))
