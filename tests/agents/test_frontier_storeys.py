"""The frontier agent in a house with two storeys: its storey memory, the stairs on its map,
and a whole episode whose target is upstairs."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from vlln.agents.frontier import FrontierAgent
from vlln.agents.frontier.crossing import Crossing
from vlln.agents.frontier.dialog import parse_storey
from vlln.agents.frontier.explorer import Explorer
from vlln.agents.frontier.mapping import ObstacleMap, Pose
from vlln.agents.frontier.planner import Planner
from vlln.agents.frontier.stairs import head_facing, stair_exits, stair_heads
from vlln.agents.frontier.storeys import Storey, StoreyMemory
from vlln.oracle.rule_oracle import RuleOracle
from vlln.sim.camera import CameraSpec
from vlln.sim.simulator import Simulator
from vlln.tasks.env import NavigationEnv
from vlln.tasks.generation import generate_house_episodes
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.taxonomy import classify
from vlln.world.frame import yaw_of
from vlln.world.generator import HouseParameters, generate_house

SMALL_TWO_STOREYS = HouseParameters(
    floors=2, min_rooms=4, max_rooms=4, min_area=60.0, max_area=70.0, clutter=0.3
)


def _storey(floor: float) -> Storey:
    obstacle_map = ObstacleMap(CameraSpec())
    return Storey(
        floor, obstacle_map, Explorer(obstacle_map, math.radians(30), np.random.default_rng(0))
    )


def _flight(obstacle_map: ObstacleMap, rise: float) -> None:
    """A flight 1 m wide along +x from x = 1 to 4.6 m, climbing ``rise`` over its length."""
    x, z = np.meshgrid(np.arange(1.0, 4.6, 0.05), np.arange(-0.5, 0.5, 0.05))
    obstacle_map.mark_stairs(x.ravel(), z.ravel(), rise * (x.ravel() - 1.0) / 3.6)


def test_a_new_storey_is_known_once_the_feet_keep_a_new_height() -> None:
    memory = StoreyMemory(_storey)
    walk = [(0.0, 0.0), (0.25, 0.0), (0.5, 0.2), (0.75, 1.4), (1.0, 2.8), (1.25, 2.8)]
    for x, height in walk:
        assert not memory.observe(x, 0.0, height)  # nearest known floor is still 0
    assert memory.observe(1.5, 0.0, 2.8)  # a second level move: a new storey
    assert [s.floor for s in memory.storeys] == [0.0, 2.8] and memory.current == 1
    assert memory.storey_of(2.75) == 1 and memory.storey_of(0.4) == 0
    assert memory.observe(1.25, 0.0, 1.2)  # back down past half way
    assert memory.current == 0 and not memory.on_floor(1.2)


def test_the_oracles_word_rules_storeys_in_and_out() -> None:
    memory = StoreyMemory(_storey)
    for x, height in [(0.0, 0.0), (0.25, 2.8), (0.5, 2.8), (0.75, 2.8), (1.0, 0.0)]:
        memory.observe(x, 0.0, height)
    assert len(memory.storeys) == 2 and memory.current == 0
    crossing = Crossing(memory, math.radians(30))
    assert crossing.fits_hint(0) and crossing.fits_hint(1)  # nothing said yet
    crossing.note_hint(1)  # "It is upstairs, take the stairs."
    assert not crossing.fits_hint(0) and crossing.fits_hint(1)
    crossing.note_hint(0)  # directions naming no storey, given on the ground floor
    assert crossing.fits_hint(0) and not crossing.fits_hint(1)


def test_flights_on_the_map_lead_up_or_down_along_their_axis() -> None:
    below, above = ObstacleMap(CameraSpec()), ObstacleMap(CameraSpec())
    _flight(below, 2.8)
    _flight(above, -2.8)
    (up,) = stair_exits(below)
    (down,) = stair_exits(above)
    assert (up.direction, down.direction) == (1, -1)
    assert up.axis == pytest.approx((1.0, 0.0), abs=1e-6)  # climbing along +x
    assert down.axis == pytest.approx((1.0, 0.0), abs=1e-6)  # dropping along +x
    assert stair_heads(below).size == 0  # its floor-level cells are the foot of the flight


def test_a_lone_floor_level_tread_is_the_head_of_a_flight_down() -> None:
    obstacle_map = ObstacleMap(CameraSpec())
    x, z = np.meshgrid(np.arange(1.0, 1.25, 0.05), np.arange(-0.5, 0.5, 0.05))
    obstacle_map.mark_stairs(x.ravel(), z.ravel(), np.zeros(x.size))
    assert stair_exits(obstacle_map) == []
    cells = np.unique(obstacle_map.flat_cells(x.ravel(), z.ravel()))
    assert np.array_equal(np.sort(stair_heads(obstacle_map)), cells)
    # Seen from the west, the flight goes down eastward, across the tread's long side.
    facing = head_facing(obstacle_map, Pose(0.0, 0.0, 0.0), (1.1, 0.0))
    assert facing == pytest.approx(yaw_of(1.0, 0.0), abs=1e-6)


def test_paths_keep_off_steep_stairs_unless_taking_them() -> None:
    obstacle_map = ObstacleMap(CameraSpec())
    obstacle_map.mark_free_disc(Pose(0.0, 0.0, 0.0), 0.3)
    _flight(obstacle_map, 2.8)
    pose = Pose(0.0, 0.0, 0.0)
    row, col = obstacle_map.cell_of(4.0, 0.0)  # high on the flight
    assert math.isinf(Planner().plan(obstacle_map, pose).distance(row, col))
    assert math.isfinite(Planner().plan(obstacle_map, pose, over_stairs=True).distance(row, col))


def test_route_answers_name_the_storey() -> None:
    assert parse_storey("It is upstairs, take the stairs. Turn left about 60 degrees.") == 1
    assert parse_storey("Turn right. 1. Go forward about 2 meters and go downstairs.") == -1
    assert parse_storey("Turn left about 60 degrees.") is None


@pytest.fixture(scope="module")
def sim() -> Iterator[Simulator]:
    with Simulator(generate_house(1, SMALL_TWO_STOREYS)) as simulator:
        yield simulator


class _OneScene(SceneCache):
    def __init__(self, simulator: Simulator) -> None:
        super().__init__()
        self.simulator = simulator

    def get(self, scene_id: str) -> Simulator:
        return self.simulator


@pytest.mark.slow
def test_it_climbs_the_stairs_to_a_target_on_the_storey_above(sim: Simulator) -> None:
    storeys = sim.storeys
    assert storeys is not None
    episodes = generate_house_episodes(sim, np.random.default_rng(0)).iign
    episode = episodes[36]
    box = sim.house.instance(int(episode.instruction.instance_id[0])).box
    assert storeys.level_of(episode.start_position[1]) == 0
    assert storeys.level_under(box.min[1]) == 1
    config = TaskConfig(task=TaskType.IIGN, dialog_budget=5)
    env = NavigationEnv([episode], config, _OneScene(sim), RuleOracle(0), privileged=True)
    observation, _ = env.reset(options={"episode_index": 0})
    agent = FrontierAgent(seed=0)
    agent.reset(env.episode_info())
    heights = []
    for _ in range(700):
        observation, _, terminated, truncated, _ = env.step(agent.act(observation))
        heights.append(float(observation["height"]))
        if terminated or truncated:
            break
    record = env.record("frontier")
    assert classify(record) == "success"
    storey_height = storeys.floor_ys[1] - storeys.floor_ys[0]
    assert heights[-1] == pytest.approx(storey_height)  # it stopped upstairs
    assert [s.floor for s in agent.memory.storeys] == pytest.approx([0.0, storey_height])
    assert agent.memory.links == {(0, 1): 1, (1, -1): 0}
    assert any("upstairs" in turn.answer for turn in record.dialog)
