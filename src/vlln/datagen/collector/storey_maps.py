"""The collector's depth-built obstacle maps: one per storey, all in the start's frame.

A storey's map is updated only while the agent stands on that storey's floor: the map keeps
heights relative to the agent's feet, so a frame taken part-way up a flight would draw the
floor ahead as a wall. Frontier goals already reached are remembered per storey, since the
same ``(x, z)`` on another storey is another place.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from vlln.agents.frontier.frontiers import find_frontiers
from vlln.agents.frontier.mapping import MapConfig, ObstacleMap, Pose
from vlln.sim.agent import AgentState
from vlln.sim.camera import CameraSpec

_START_DISC = 0.3  # m around the agent marked free where a storey's map begins


class StoreyMaps:
    """Obstacle maps by storey, with the frontier points each still offers."""

    def __init__(self, camera: CameraSpec, config: MapConfig, origin: tuple[float, float]):
        self.camera = camera
        self.config = config
        self.origin = origin  # the start's (x, z): map coordinates are relative to it
        self.maps: dict[int, ObstacleMap] = {}
        self.visited: dict[int, list[tuple[float, float]]] = {}  # world (x, z) per storey

    def of(self, level: int, state: AgentState) -> ObstacleMap:
        """The storey's map; a new one starts with the floor under the agent marked free."""
        found = self.maps.get(level)
        if found is None:
            found = self.maps[level] = ObstacleMap(self.camera, self.config)
            found.mark_free_disc(self.pose(state), _START_DISC)
        return found

    def pose(self, state: AgentState) -> Pose:
        x, _, z = state.position
        return Pose(x - self.origin[0], z - self.origin[1], state.yaw)

    def explored_at(self, level: int, x: float, z: float) -> bool:
        """Whether the storey's map has seen the world point ``(x, z)``."""
        grid = self.maps[level]
        row, col = grid.cell_of(x - self.origin[0], z - self.origin[1])
        rows, cols = grid.shape
        return 0 <= row < rows and 0 <= col < cols and bool(grid.explored[row, col])

    def visit(self, level: int, *points: tuple[float, float]) -> None:
        """Remember world ``(x, z)`` points whose frontiers are not to be chosen again."""
        self.visited.setdefault(level, []).extend(points)

    def frontier_points(
        self,
        level: int,
        min_frontier_cells: int,
        min_pocket_area: float,
        visited_radius: float,
    ) -> NDArray[np.float64]:
        """Frontier points of the storey's map in map coordinates, minus those near goals
        already visited there."""
        grid = self.maps[level]
        box = grid.box(2)
        explored = grid.explored[box.r0 : box.r1, box.c0 : box.c1]
        obstacle = grid.obstacle[box.r0 : box.r1, box.c0 : box.c1]
        pocket = math.ceil(min_pocket_area / grid.cell_size**2)
        found = find_frontiers(explored & ~obstacle, explored, min_frontier_cells, pocket)
        points = np.array(
            [grid.cell_centre(box.r0 + f.row, box.c0 + f.col) for f in found], np.float64
        ).reshape(-1, 2)
        visited = self.visited.get(level, [])
        if visited and points.shape[0]:
            near = np.array(visited) - np.array(self.origin)
            gaps = np.hypot(
                points[:, None, 0] - near[None, :, 0], points[:, None, 1] - near[None, :, 1]
            )
            points = points[gaps.min(axis=1) > visited_radius]
        return points
