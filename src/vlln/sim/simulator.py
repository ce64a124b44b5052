"""The simulator: one house, one agent, one camera.

It ties the pieces together: the renderer draws the house from the agent's camera, the
navigable grid keeps the agent on the floor, and geodesic fields answer "how far is it" in
O(1) once built. Fields are cached per goal set because a task asks the same question about
the same goals at every step.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from vlln.errors import ConfigError, NavigationError
from vlln.sim.agent import Action, AgentState, MotionConfig, step
from vlln.sim.camera import CameraSpec
from vlln.sim.geodesic import GeodesicField
from vlln.sim.navgrid import NavGrid
from vlln.sim.renderer import Frame, Renderer
from vlln.sim.storey_field import StoreyField
from vlln.sim.storeys import Storeys
from vlln.sim.viewpoints import GoalPoint, storey_view_points, view_points
from vlln.world.model import Box3, House

Point2 = tuple[float, float]
Field = GeodesicField | StoreyField


@dataclass(frozen=True)
class NavigationConfig:
    """How the navigable grid is derived from the geometry (docs/reference-facts.md §1)."""

    cell_size: float = 0.05
    agent_radius: float = 0.18
    agent_height: float = 1.5
    step_height: float = 0.15


@dataclass(frozen=True)
class SimulatorConfig:
    camera: CameraSpec = field(default_factory=CameraSpec)
    motion: MotionConfig = field(default_factory=MotionConfig)
    navigation: NavigationConfig = field(default_factory=NavigationConfig)
    field_cache_size: int = 8  # geodesic fields kept per simulator


@dataclass(frozen=True)
class Observation:
    """What one step produced: the camera frame, the agent's state and whether it collided."""

    frame: Frame
    state: AgentState
    collided: bool


class Simulator:
    """Moves an agent through a house and renders what its camera sees."""

    def __init__(self, house: House, config: SimulatorConfig | None = None) -> None:
        if house.geometry is None:
            raise ConfigError(
                f"house {house.name!r} has no geometry to simulate; generate it with "
                "vlln.world.generator.generate_house or import one with geometry"
            )
        self.house = house
        self.config = config or SimulatorConfig()
        nav = self.config.navigation
        floor_y = min((room.floor_y for room in house.rooms), default=0.0)
        floor_ys = sorted({room.floor_y for room in house.rooms})
        flights = [inst.id for inst in house.instances if inst.category == "stairs"]
        self.storeys: Storeys | None = None
        self._grid: NavGrid | None = None
        if len(floor_ys) > 1:  # storeys no flight joins stay apart, never flattened
            self.storeys = Storeys.from_mesh(
                house.geometry.mesh,
                floor_ys,
                flights,
                cell_size=nav.cell_size,
                agent_radius=nav.agent_radius,
                agent_height=nav.agent_height,
                step_height=nav.step_height,
            )
        else:
            self._grid = NavGrid.from_mesh(
                house.geometry.mesh,
                floor_y=floor_y,
                cell_size=nav.cell_size,
                agent_radius=nav.agent_radius,
                agent_height=nav.agent_height,
                step_height=nav.step_height,
            )
        self.renderer = Renderer(house.geometry.mesh, self.config.camera)
        self._fields: OrderedDict[tuple[tuple[tuple[float, ...], ...], float], Field] = (
            OrderedDict()
        )
        self._state = AgentState(position=(0.0, floor_y, 0.0), yaw=0.0, tilt=0.0)

    @property
    def state(self) -> AgentState:
        return self._state

    @property
    def grid(self) -> NavGrid:
        """The navigable grid of a one-storey house."""
        if self._grid is None:
            storeys = len(self.storeys.grids) if self.storeys is not None else 0
            raise NavigationError(
                f"{self.house.name} has {storeys} storeys and this feature works "
                "on one storey; use a one-storey house (floors=1)"
            )
        return self._grid

    @property
    def nav(self) -> Storeys | NavGrid:
        """Where the agent can walk: the storeys of the house, or the grid of its one storey."""
        return self.storeys if self.storeys is not None else self.grid

    def reset(self, state: AgentState) -> Observation:
        """Put the agent at ``state`` (which must be navigable) and render its view."""
        x, y, z = state.position
        plane = self.storeys.grid_at(y) if self.storeys is not None else self.grid
        if not plane.is_navigable(x, z):
            sx, sz = plane.snap_point(x, z)
            raise ConfigError(
                f"start position ({x:.3f}, {z:.3f}) is not navigable in {self.house.name}; "
                f"the nearest navigable point is ({sx:.3f}, {sz:.3f})"
            )
        self._state = state
        return Observation(self.render(), state, collided=False)

    def step(self, action: Action) -> Observation:
        """Apply one action, then render the new view."""
        result = step(self._state, action, self.nav, self.config.motion)
        self._state = result.state
        return Observation(self.render(), result.state, result.collided)

    def move(self, action: Action) -> bool:
        """Apply one action without rendering; returns whether it collided."""
        result = step(self._state, action, self.nav, self.config.motion)
        self._state = result.state
        return result.collided

    def render(self, state: AgentState | None = None) -> Frame:
        s = self._state if state is None else state
        return self.renderer.render(s.position, s.yaw, s.tilt)

    def render_instance_ids(self, state: AgentState) -> NDArray[np.int32]:
        """The instance-id image of :meth:`render` alone (cheaper: one read-back)."""
        return self.renderer.render_instance_ids(state.position, state.yaw, state.tilt)

    def view_points(self, box: Box3) -> list[GoalPoint]:
        """Where an object in ``box`` counts as reached (:mod:`vlln.sim.viewpoints`):
        ``(x, z)`` on one storey, ``(x, y, z)`` on its storey in a house with several."""
        if self.storeys is not None:
            return list(storey_view_points(self.storeys, box))
        return list(view_points(self.grid, box))

    def geodesic_field(self, goals: Sequence[Sequence[float]]) -> GeodesicField:
        """The distance field to ``(x, z)`` goals on a one-storey house, built once, cached."""
        built = self.distance_field([(goal[0], goal[-1]) for goal in goals], one_storey=True)
        if not isinstance(built, GeodesicField):
            raise NavigationError("geodesic_field works on one storey; use distance_field")
        return built

    def distance_field(
        self, goals: Sequence[Sequence[float]], one_storey: bool = False, limit: float = math.inf
    ) -> Field:
        """The distance field to a goal set, built once and then cached. Goals are ``(x, z)``
        on one storey and ``(x, y, z)`` in a house with several. Cells farther than ``limit``
        metres from every goal read ``inf`` (:class:`GeodesicField`)."""
        if one_storey:
            self.grid  # noqa: B018 - refuses a house with several storeys
        points = tuple(tuple(float(v) for v in goal) for goal in goals)
        key = (points, float(limit))
        cached = self._fields.get(key)
        if cached is not None:
            self._fields.move_to_end(key)
            return cached
        built: Field
        if self.storeys is not None:
            built = StoreyField(self.storeys, list(points), limit)
        else:
            built = GeodesicField(self.grid, [(goal[0], goal[-1]) for goal in points], limit)
        self._fields[key] = built
        if len(self._fields) > self.config.field_cache_size:
            self._fields.popitem(last=False)
        return built

    def close(self) -> None:
        self.renderer.close()

    def __enter__(self) -> Simulator:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
