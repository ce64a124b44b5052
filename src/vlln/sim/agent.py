"""The agent's body: its state, its discrete actions, and how an action moves it.

Motion follows the benchmark (FORWARD 0.25 m, turns of 30 degrees, a tilting camera) with
collisions that slide along walls as habitat-sim's "allow sliding" does: a blocked move keeps
the part of the motion along the blocking boundary. The agent is a point on the navigable
grid, whose cells already keep the body's radius clear of obstacles.

Angles: ``yaw`` as in :mod:`vlln.world.frame` (0 looks along -z, positive = turned left);
``tilt`` is the camera pitch, positive looking up. Both in radians.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

from pydantic import Field

from vlln.config import Positive, settings_dataclass
from vlln.errors import ConfigError, DataFormatError
from vlln.sim.navgrid import NavGrid, Point2
from vlln.sim.storeys import Storeys
from vlln.world.frame import heading_vector, wrap_angle, yaw_to_quaternion

Point3 = tuple[float, float, float]

# Forward moves are made in sub-steps of this many cells.
_SUBSTEP_CELLS = 0.5
# Tolerance for comparing a tilt with its limits after repeated float additions.
_TILT_TOLERANCE = 1e-9


class Action(IntEnum):
    """Discrete motion actions; the values are those of the released trajectories."""

    STOP = 0
    MOVE_FORWARD = 1
    TURN_LEFT = 2
    TURN_RIGHT = 3
    LOOK_UP = 4
    LOOK_DOWN = 5


@dataclass(frozen=True)
class AgentState:
    """Where the agent stands and looks. ``position`` is (x, y, z) with y the floor height."""

    position: Point3
    yaw: float = 0.0
    tilt: float = 0.0

    def __post_init__(self) -> None:
        # A value object built on every step of every episode: it guards itself (pydantic: 3x).
        position = self.position
        if type(position) is not tuple:  # a list from a caller: keep states hashable
            object.__setattr__(self, "position", tuple(position))
            position = self.position
        isfinite = math.isfinite
        if not (
            len(position) == 3
            and isfinite(position[0])
            and isfinite(position[1])
            and isfinite(position[2])
            and isfinite(self.yaw)
            and isfinite(self.tilt)
        ):
            raise ConfigError(
                f"an agent state needs a finite (x, y, z) position, yaw and tilt; got "
                f"position={position}, yaw={self.yaw}, tilt={self.tilt}"
            )

    @property
    def rotation(self) -> list[float]:
        """Heading as a quaternion ``[x, y, z, w]`` (the camera tilt is not included)."""
        return yaw_to_quaternion(self.yaw)

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON-ready record; :meth:`from_dict` restores it bit for bit."""
        return {"position": list(self.position), "yaw": self.yaw, "tilt": self.tilt}

    @staticmethod
    def from_dict(record: Mapping[str, Any]) -> AgentState:
        expected = {"position", "yaw", "tilt"}
        if set(record) != expected:
            raise DataFormatError(
                f"an agent state record has keys {sorted(expected)}, got {sorted(record)}"
            )
        position = record["position"]
        try:
            x, y, z = (float(v) for v in position)
            return AgentState((x, y, z), float(record["yaw"]), float(record["tilt"]))
        except (TypeError, ValueError) as error:
            raise DataFormatError(f"invalid agent state record {dict(record)!r}: {error}") from None


@settings_dataclass
class MotionConfig:
    """Step sizes and camera limits (degrees for angles, as people write them)."""

    forward_step: Positive = 0.25
    turn_deg: float = Field(default=30.0, gt=0.0, le=180.0)
    tilt_step_deg: Positive = 30.0
    min_tilt_deg: float = Field(default=-60.0, ge=-90.0, le=0.0)
    max_tilt_deg: float = Field(default=30.0, ge=0.0, le=90.0)

    @property
    def turn(self) -> float:
        """One turn step in radians."""
        return math.radians(self.turn_deg)


@dataclass(frozen=True)
class StepResult:
    """The state after an action; ``collided`` when a move fell short of its full length."""

    state: AgentState
    collided: bool


def step(
    state: AgentState, action: Action, grid: NavGrid | Storeys, config: MotionConfig
) -> StepResult:
    """Apply one action. Only MOVE_FORWARD can collide; STOP changes nothing.

    With several storeys the move is made on the storey of the agent's height, and the
    height then follows that storey's floor or the steps under the agent.
    """
    if action == Action.MOVE_FORWARD:
        if isinstance(grid, Storeys):
            level = grid.level_of(state.position[1])
            moved = _forward(state, grid.grids[level], config.forward_step)
            x, _, z = moved.state.position
            position = (x, grid.height_at(level, x, z), z)
            return StepResult(AgentState(position, state.yaw, state.tilt), moved.collided)
        return _forward(state, grid, config.forward_step)
    if action in (Action.TURN_LEFT, Action.TURN_RIGHT):
        sign = 1.0 if action == Action.TURN_LEFT else -1.0
        yaw = wrap_angle(state.yaw + sign * config.turn)
        return StepResult(AgentState(state.position, yaw, state.tilt), False)
    if action in (Action.LOOK_UP, Action.LOOK_DOWN):
        sign = 1.0 if action == Action.LOOK_UP else -1.0
        tilt = state.tilt + sign * math.radians(config.tilt_step_deg)
        low = math.radians(config.min_tilt_deg) - _TILT_TOLERANCE
        high = math.radians(config.max_tilt_deg) + _TILT_TOLERANCE
        if not low <= tilt <= high:
            return StepResult(state, False)
        return StepResult(AgentState(state.position, state.yaw, tilt), False)
    if action == Action.STOP:
        return StepResult(state, False)
    raise ConfigError(f"unknown action {action!r}; use one of {[a.name for a in Action]}")


def _forward(state: AgentState, grid: NavGrid, distance: float) -> StepResult:
    """Move along the heading; once blocked, go on in sub-steps of half a cell that slide.

    Each cast walks every cell on the way, so the agent never crosses a blocked cell. A
    sub-step stopped at a cell boundary of constant x (or z) keeps the rest of its motion
    along z (or x); sliding sub-step by sub-step also follows staircase (diagonal) boundaries.
    """
    x, y, z = state.position
    hx, hz = heading_vector(state.yaw)
    cast = grid.cast(x, z, hx * distance, hz * distance)
    x, z = cast.x, cast.z
    if cast.axis >= 0:
        rest = distance * (1.0 - cast.fraction)
        count = max(1, math.ceil(rest / (grid.cell_size * _SUBSTEP_CELLS)))
        x, z = _slide(grid, x, z, hx * rest / count, hz * rest / count, count)
    return StepResult(AgentState((x, y, z), state.yaw, state.tilt), cast.axis >= 0)


def _slide(grid: NavGrid, x: float, z: float, dx: float, dz: float, count: int) -> Point2:
    """Make ``count`` sub-steps of ``(dx, dz)``; a blocked one keeps its motion along the
    boundary that stopped it."""
    for _ in range(count):
        cast = grid.cast(x, z, dx, dz)
        if cast.axis >= 0:
            remaining = 1.0 - cast.fraction
            if cast.axis == 0:
                cast = grid.cast(cast.x, cast.z, 0.0, dz * remaining)
            else:
                cast = grid.cast(cast.x, cast.z, dx * remaining, 0.0)
            if cast.x == x and cast.z == z:
                break  # wedged: every later sub-step would be blocked the same way
        x, z = cast.x, cast.z
    return x, z
