from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tests.sim import scenes
from vlln.errors import ConfigError, DataFormatError, NavigationError
from vlln.sim.agent import Action, AgentState, MotionConfig, step
from vlln.sim.navgrid import NavGrid
from vlln.world.frame import quaternion_to_yaw, yaw_of

MOTION = MotionConfig()


@pytest.fixture(scope="module")
def room() -> NavGrid:
    return NavGrid.from_mesh(scenes.empty_room(6.0, 4.0))


def _random_walk(
    grid: NavGrid, state: AgentState, actions: list[Action]
) -> list[tuple[AgentState, bool]]:
    out = []
    for action in actions:
        result = step(state, action, grid, MOTION)
        state = result.state
        out.append((state, result.collided))
    return out


def _random_actions(rng: np.random.Generator, n: int) -> list[Action]:
    choices = [Action.MOVE_FORWARD, Action.TURN_LEFT, Action.TURN_RIGHT, Action.LOOK_UP]
    return [
        Action(int(a)) for a in rng.choice([int(c) for c in choices], n, p=[0.7, 0.13, 0.13, 0.04])
    ]


@pytest.mark.parametrize("scene", ["furnished_room", "l_shaped_rooms", "divided_room"])
def test_random_actions_never_leave_the_navigable_area(scene: str) -> None:
    grid = NavGrid.from_mesh(getattr(scenes, scene)())
    rng = np.random.default_rng(21)
    for _ in range(3):
        x, z = grid.sample_navigable_point(rng)
        state = AgentState((x, 0.0, z), float(rng.uniform(-math.pi, math.pi)))
        previous = state
        for current, _ in _random_walk(grid, state, _random_actions(rng, 1500)):
            px, _, pz = current.position
            assert grid.is_navigable(px, pz)
            assert math.dist((px, pz), (previous.position[0], previous.position[2])) <= 0.25 + 1e-9
            previous = current


def test_a_thin_wall_is_never_crossed() -> None:
    # One blocked column of cells: the agent must stay on its side whatever it does.
    navigable = np.ones((40, 40), bool)
    navigable[:, 20] = False
    grid = NavGrid(navigable, (0.0, 0.0), 0.05)
    rng = np.random.default_rng(3)
    for yaw in np.linspace(-math.pi, math.pi, 37):
        start = AgentState((0.9, 0.0, 1.0), float(yaw))
        for state, _ in _random_walk(grid, start, _random_actions(rng, 60)):
            assert state.position[0] < 1.0


def test_forward_in_open_space_moves_a_full_step_along_the_heading(room: NavGrid) -> None:
    for yaw in [0.0, math.pi / 2, -math.pi / 3, 2.5]:
        start = AgentState((3.0, 0.0, 2.0), yaw)
        result = step(start, Action.MOVE_FORWARD, room, MOTION)
        x, y, z = result.state.position
        assert not result.collided
        assert math.hypot(x - 3.0, z - 2.0) == pytest.approx(0.25, abs=1e-12)
        assert yaw_of(x - 3.0, z - 2.0) == pytest.approx(yaw, abs=1e-9)
        assert y == 0.0
    # Yaw 0 looks along -z; a positive yaw has turned left, toward -x.
    assert step(AgentState((3.0, 0.0, 2.0), 0.0), Action.MOVE_FORWARD, room, MOTION).state.position[
        2
    ] == pytest.approx(1.75)
    left = step(AgentState((3.0, 0.0, 2.0), math.pi / 2), Action.MOVE_FORWARD, room, MOTION)
    assert left.state.position[0] == pytest.approx(2.75)


@pytest.mark.parametrize(
    ("start", "along", "into"),
    [
        ((1.0, 0.6), (1.0, 0.0), (0.0, -1.0)),  # east along the south wall (z = 0)
        ((5.0, 3.4), (-1.0, 0.0), (0.0, 1.0)),  # west along the north wall (z = 4)
        ((0.6, 3.0), (0.0, -1.0), (-1.0, 0.0)),  # south along the west wall (x = 0)
        ((5.4, 1.0), (0.0, 1.0), (1.0, 0.0)),  # north along the east wall (x = 6)
    ],
)
def test_sliding_along_a_wall_at_a_shallow_angle(
    room: NavGrid,
    start: tuple[float, float],
    along: tuple[float, float],
    into: tuple[float, float],
) -> None:
    angle = math.radians(20.0)  # heading 20 degrees off the wall, toward it
    c, s = math.cos(angle), math.sin(angle)
    yaw = yaw_of(c * along[0] + s * into[0], c * along[1] + s * into[1])
    state = AgentState((start[0], 0.0, start[1]), yaw)
    touched = False
    for _ in range(10):
        before = state.position
        result = step(state, Action.MOVE_FORWARD, room, MOTION)
        state = result.state
        progress = (state.position[0] - before[0]) * along[0] + (
            state.position[2] - before[2]
        ) * along[1]
        if result.collided:
            touched = True
            # Sliding keeps (about) the full component of the step along the wall.
            assert progress == pytest.approx(0.25 * c, abs=0.01)
        else:
            assert not touched  # once at the wall, every step collides
            assert progress == pytest.approx(0.25 * c, abs=1e-9)
    assert touched
    x, z = state.position[0], state.position[2]
    assert room.is_navigable(x, z)
    assert not room.is_navigable(x + 0.06 * into[0], z + 0.06 * into[1])


def test_walking_into_a_wall_head_on_stops_and_reports_a_collision(room: NavGrid) -> None:
    state = AgentState((3.0, 0.0, 0.4), 0.0)  # facing -z, the south wall
    for _ in range(4):
        result = step(state, Action.MOVE_FORWARD, room, MOTION)
        state = result.state
    assert result.collided
    again = step(state, Action.MOVE_FORWARD, room, MOTION)
    assert again.collided and again.state.position == pytest.approx(state.position, abs=1e-6)


def test_twelve_turns_return_to_the_start_yaw(room: NavGrid) -> None:
    for yaw in [0.0, 0.3, -2.9, math.pi]:
        for action in (Action.TURN_LEFT, Action.TURN_RIGHT):
            state = AgentState((3.0, 0.0, 2.0), yaw)
            seen = []
            for _ in range(12):
                state = step(state, action, room, MOTION).state
                assert -math.pi < state.yaw <= math.pi
                seen.append(state.yaw)
            assert math.cos(state.yaw - yaw) == pytest.approx(1.0, abs=1e-12)
            assert abs(math.remainder(state.yaw - yaw, 2 * math.pi)) < 1e-9
            assert len({round(s, 6) for s in seen}) == 12
    left = step(AgentState((3.0, 0.0, 2.0), 0.0), Action.TURN_LEFT, room, MOTION).state
    assert left.yaw == pytest.approx(math.radians(30.0))


def test_tilt_stays_within_its_limits(room: NavGrid) -> None:
    state = AgentState((3.0, 0.0, 2.0))
    up = step(state, Action.LOOK_UP, room, MOTION).state
    assert up.tilt == pytest.approx(math.radians(30.0))
    assert step(up, Action.LOOK_UP, room, MOTION).state == up  # at the limit: no change
    down = state
    for _ in range(5):
        down = step(down, Action.LOOK_DOWN, room, MOTION).state
        assert math.radians(-60.0) - 1e-9 <= down.tilt <= 0.0
    assert down.tilt == pytest.approx(math.radians(-60.0))
    back = step(step(down, Action.LOOK_UP, room, MOTION).state, Action.LOOK_UP, room, MOTION)
    assert back.state.tilt == pytest.approx(0.0, abs=1e-12)


def test_stop_and_look_change_nothing_else(room: NavGrid) -> None:
    state = AgentState((3.0, 0.0, 2.0), 0.7, 0.0)
    assert step(state, Action.STOP, room, MOTION) == step(state, Action.STOP, room, MOTION)
    assert step(state, Action.STOP, room, MOTION).state == state
    looked = step(state, Action.LOOK_DOWN, room, MOTION).state
    assert (looked.position, looked.yaw) == (state.position, state.yaw)


def test_state_records_round_trip_exactly() -> None:
    rng = np.random.default_rng(9)
    for _ in range(200):
        x, y, z, yaw, tilt = (float(v) for v in rng.normal(0.0, 10.0, 5))
        state = AgentState((x, y, z), yaw, tilt)
        assert AgentState.from_dict(state.to_dict()) == state
        assert AgentState.from_dict(json.loads(json.dumps(state.to_dict()))) == state
    state = AgentState((1.0, 0.0, 2.0), 1.1)
    assert quaternion_to_yaw(state.rotation) == pytest.approx(1.1)
    assert AgentState([1.0, 0.0, 2.0], 1.1) == state  # type: ignore[arg-type]
    assert hash(AgentState([1.0, 0.0, 2.0], 1.1)) == hash(state)  # type: ignore[arg-type]


def test_restoring_a_state_replays_the_same_trajectory() -> None:
    grid = NavGrid.from_mesh(scenes.furnished_room())
    rng = np.random.default_rng(12)
    x, z = grid.sample_navigable_point(rng)
    start = AgentState((x, 0.0, z), 0.4)
    first = _random_walk(grid, start, _random_actions(rng, 300))
    checkpoint = first[150][0]
    tail = _random_actions(np.random.default_rng(13), 150)
    resumed = _random_walk(
        grid, AgentState.from_dict(json.loads(json.dumps(checkpoint.to_dict()))), tail
    )
    original = _random_walk(grid, checkpoint, tail)
    assert resumed == original
    assert any(collided for _, collided in original) or len(original) == 150


def test_bad_records_and_configs_are_rejected(room: NavGrid) -> None:
    with pytest.raises(DataFormatError, match="keys"):
        AgentState.from_dict({"position": [0.0, 0.0, 0.0], "yaw": 0.0})
    with pytest.raises(DataFormatError, match="invalid"):
        AgentState.from_dict({"position": [0.0, 0.0], "yaw": 0.0, "tilt": 0.0})
    with pytest.raises(ConfigError, match="finite"):
        AgentState((math.nan, 0.0, 0.0))
    with pytest.raises(ConfigError, match="forward_step"):
        MotionConfig(forward_step=-0.25)
    with pytest.raises(ConfigError, match="turn_deg"):
        MotionConfig(turn_deg=0.0)
    with pytest.raises(ConfigError, match="min_tilt_deg"):
        MotionConfig(min_tilt_deg=10.0)
    with pytest.raises(NavigationError, match="off the navigable area"):
        step(AgentState((0.0, 0.0, 0.0)), Action.MOVE_FORWARD, room, MOTION)
