"""A small hand-made trajectory dataset in a real house, walked and rendered by a Simulator.

Three trajectories, written with the dataset's own HouseWriter:

* episode 0, "golden": two left turns, four forward steps, a right turn, STOP; questions at
  frames 0 and 6. Its start is chosen so the four steps cross open floor.
* episode 1, "walk": the greedy follower toward a point several metres away (real zig-zags,
  turns between forward steps), questions at its first, middle and last frame.
* episode 2, "scan": eight left turns, three right turns (a question at frame 9), one forward
  step, a right turn, STOP.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from vlln.datagen.layout import house_dir_name
from vlln.datagen.sft import export_sft
from vlln.datagen.trajectory import Exchange, Step, Trajectory
from vlln.datagen.views import down_views, final_down_view
from vlln.datagen.writer import HouseWriter
from vlln.prompt.images import stored_frame
from vlln.sim.agent import Action, AgentState
from vlln.sim.follower import GreedyFollower
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import Episode, Instruction
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.world.frame import heading_vector, yaw_to_quaternion

HOUSE_SEED = 3
CATEGORY = "bathtub"
L, R, F, S = Action.TURN_LEFT, Action.TURN_RIGHT, Action.MOVE_FORWARD, Action.STOP
GOLDEN_ACTIONS = [L, L, F, F, F, F, R, S]
GOLDEN_DIALOG = [
    (0, "What colour is the bathtub?", "It is white."),
    (6, "Is the bathtub in the room on my right?", "Yes, it is."),
]
SCAN_ACTIONS = [L] * 8 + [R] * 3 + [F, R, S]
SCAN_DIALOG = [(9, "Which way is the bathtub?", "Turn right about 60 degrees.")]
TURN = math.radians(30.0)


@dataclass(frozen=True)
class HandDataset:
    root: Path
    house: str  # the house folder name
    states: dict[int, list[AgentState]]  # frame states by episode index
    actions: dict[int, list[Action]]  # the action done at each frame, by episode index
    names: dict[int, str]  # episode ids by episode index
    dialogs: dict[int, list[tuple[int, str, str]]]  # (frame, question, answer) by episode


@pytest.fixture(scope="session")
def sim() -> Iterator[Simulator]:
    cache = SceneCache(capacity=1)
    yield cache.get(procedural_scene_id(HOUSE_SEED))
    cache.close()


@pytest.fixture(scope="session")
def hand_dataset(sim: Simulator, tmp_path_factory: pytest.TempPathFactory) -> HandDataset:
    root = tmp_path_factory.mktemp("hand_dataset")
    scene_id = procedural_scene_id(HOUSE_SEED)
    writer = HouseWriter(root / "trajectories", scene_id, sim.config.camera)
    golden_start = clear_start(sim, turns=2, distance=1.3)
    walk_actions = follower_actions(sim, golden_start)
    last = len(walk_actions) - 1
    walk_dialog = [
        (0, "Is the bathtub white?", "Yes."),
        (last // 2, "Where should I go next?", "Keep going forward."),
        (last, "Is this the bathtub?", "Yes, this is it."),
    ]
    plans = [
        ("golden", golden_start, GOLDEN_ACTIONS, GOLDEN_DIALOG),
        ("walk", golden_start, walk_actions, walk_dialog),
        ("scan", clear_start(sim, turns=5, distance=0.5), SCAN_ACTIONS, SCAN_DIALOG),
    ]
    states: dict[int, list[AgentState]] = {}
    actions_of: dict[int, list[Action]] = {}
    names: dict[int, str] = {}
    dialogs: dict[int, list[tuple[int, str, str]]] = {}
    for name, start, actions, dialog in plans:
        trajectory = walk(sim, name, start, actions, dialog)
        index = writer.write_kept(
            trajectory,
            level_views(sim, trajectory),
            down_views(sim, trajectory, final_down_view(sim, trajectory)),
        )
        states[index] = [step.state for step in trajectory.steps]
        actions_of[index] = list(actions)
        names[index] = name
        dialogs[index] = list(dialog)
    writer.finish({})
    return HandDataset(root, house_dir_name(scene_id), states, actions_of, names, dialogs)


def clear_start(sim: Simulator, turns: int, distance: float) -> AgentState:
    """A start whose heading after ``turns`` left turns has ``distance`` m of open floor."""
    grid = sim.grid
    floor_y = sim.state.position[1]
    cells = grid.free_cells()
    for index in range(len(cells) // 2, len(cells), 53):
        x, z = grid.cell_to_world(int(cells[index][0]), int(cells[index][1]))
        for k in range(12):
            hx, hz = heading_vector((k + turns) * TURN)
            dx, dz = hx * distance, hz * distance
            sides = ((0.0, 0.0), (-hz * 0.3, hx * 0.3), (hz * 0.3, -hx * 0.3))
            wide = all(
                grid.segment_is_clear(x + ox, z + oz, x + ox + dx, z + oz + dz) for ox, oz in sides
            )
            if wide:
                return AgentState((x, floor_y, z), k * TURN, 0.0)
    raise AssertionError("no open floor in the test house")


def follower_actions(sim: Simulator, start: AgentState, limit: int = 60) -> list[Action]:
    """The greedy follower's actions from ``start`` toward a point 4-7 m away, then STOP."""
    grid = sim.grid
    x0, _, z0 = start.position
    rng = np.random.default_rng(HOUSE_SEED)
    component = grid.component_of(x0, z0)
    for _ in range(200):
        goal = grid.sample_navigable_point(rng, component)
        field = sim.geodesic_field([goal])
        if 4.0 <= field.distance(x0, z0) <= 7.0:
            break
    follower = GreedyFollower(grid, field, 0.25, sim.config.motion)
    sim.reset(start)
    actions: list[Action] = []
    while len(actions) < limit:
        action = follower.next_action(sim.state)
        if action == Action.STOP:
            break
        actions.append(action)
        sim.move(action)
    return [*actions, Action.STOP]


def walk(
    sim: Simulator,
    name: str,
    start: AgentState,
    actions: Sequence[Action],
    dialog: Sequence[tuple[int, str, str]],
    category: str = CATEGORY,
    target: str = "1",
) -> Trajectory:
    q = yaw_to_quaternion(start.yaw)
    episode = Episode(
        episode_id=name,
        scene_id=procedural_scene_id(HOUSE_SEED),
        start_position=start.position,
        start_rotation=(q[0], q[1], q[2], q[3]),
        object_category=category,
        goals=(),
        instruction=Instruction("iign", f"Search for the {category}.", (target,)),
    )
    trajectory = Trajectory(episode)
    sim.reset(start)
    for action in actions:
        state = sim.state
        collided = False if action == Action.STOP else sim.move(action)
        trajectory.steps.append(Step(state, action, collided, 0.0))
    assert not any(step.collided for step in trajectory.steps), name
    trajectory.dialog = [
        Exchange(frame, "route", question, answer, "route") for frame, question, answer in dialog
    ]
    return trajectory


def level_views(sim: Simulator, trajectory: Trajectory) -> list[bytes]:
    """Every step's level view as the data set stores it."""
    return [
        stored_frame(sim.render(AgentState(step.state.position, step.state.yaw, 0.0)).rgb)
        for step in trajectory.steps
    ]


@pytest.fixture(scope="session")
def default_export(hand_dataset: HandDataset, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The hand-made dataset exported with the default settings."""
    out = tmp_path_factory.mktemp("sft_default")
    export_sft(hand_dataset.root, out, progress=False)
    return out
