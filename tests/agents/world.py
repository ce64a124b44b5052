"""A two-room house with two chairs, playable by NavigationEnv, built in about a second.

Room A (6 x 4 m, z 0..4) and room B (3 x 5 m, north of A's west half) share a wall with a
door at x 1..2 (:func:`tests.sim.scenes.l_shaped_rooms`). A red chair stands in room A's
east end and a blue one in room B, so a target can be in view from a start or behind the door.
"""

from __future__ import annotations

import math

import numpy as np

from tests.sim import scenes
from vlln.agents.protocol import Agent
from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.tasks.oracle_protocol import EpisodeContext, Question, QuestionType, Reply
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import AgentOutput, TaskConfig, TaskType
from vlln.world.frame import wrap_angle, yaw_of, yaw_to_quaternion
from vlln.world.mesh import Mesh
from vlln.world.model import Attributes, Box3, House, HouseGeometry, ObjectInstance, Room

RED_CHAIR = 1
BLUE_CHAIR = 2
SCENE_ID = "test/two_rooms"


def chair(instance_id: int, colour: str, x: float, z: float, room: int) -> ObjectInstance:
    box = Box3((x - 0.25, 0.0, z - 0.25), (x + 0.25, 0.9, z + 0.25))
    return ObjectInstance(
        instance_id, "chair", "chair", Attributes(color=colour), f"a {colour} chair", box, room
    )


def two_room_house() -> House:
    chairs = [chair(RED_CHAIR, "red", 5.0, 1.0, 0), chair(BLUE_CHAIR, "blue", 1.5, 7.5, 1)]
    parts = [scenes.l_shaped_rooms()]
    for placed in chairs:
        x, _, z = placed.box.center
        parts.append(scenes.box_object(placed.id, x, z, (0.5, 0.9, 0.5)))
    rooms = [
        Room(0, "living room", ((0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (0.0, 4.0))),
        Room(1, "bedroom", ((0.0, 4.0), (3.0, 4.0), (3.0, 9.0), (0.0, 9.0))),
    ]
    return House("two_rooms", rooms, [], chairs, geometry=HouseGeometry(Mesh.concatenate(parts)))


class OneScene(SceneCache):
    """A scene cache that always hands out the same simulator."""

    def __init__(self, simulator: Simulator) -> None:
        super().__init__()
        self.simulator = simulator

    def get(self, scene_id: str) -> Simulator:
        return self.simulator


def episode(
    sim: Simulator,
    target: int,
    start: tuple[float, float],
    yaw: float,
    text: str = "Search for the chair.",
) -> Episode:
    instance = sim.house.instance(target)
    points = view_points(sim.grid, instance.box)
    box = instance.box
    goal = Goal(
        instance.position,
        None,
        (*box.min, *box.max),
        tuple(ViewPoint((x, 0.0, z)) for x, z in points),
    )
    return Episode(
        episode_id=f"{target}_{start[0]}_{start[1]}",
        scene_id=SCENE_ID,
        start_position=(start[0], 0.0, start[1]),
        start_rotation=tuple(yaw_to_quaternion(yaw)),  # type: ignore[arg-type]
        object_category="chair",
        goals=(goal,),
        instruction=Instruction("iign", text, (str(target),), None),
    )


class ColourOracle:
    """Answers colour, "is this the one?" (the target most seen in the image centre, within
    3 m) and "which way?" (the straight-line direction) questions."""

    def start(self, context: EpisodeContext) -> None:
        self.target = context.target

    def answer(self, question: Question) -> Reply:
        text = question.text.lower()
        target = self.target
        x, _, z = question.state.position
        cx, _, cz = target.box.center
        if "color" in text:
            return Reply(f"It is {target.attributes.color}.", QuestionType.ATTRIBUTE)
        if text.startswith("is this"):
            ids = question.frame.instance_ids
            h, w = ids.shape
            centre = ids[h // 4 : 3 * h // 4, w // 4 : 3 * w // 4]
            seen = int(np.count_nonzero(centre == target.id))
            near = math.hypot(cx - x, cz - z) <= 3.0
            yes = seen >= 200 and near
            return Reply("Yes." if yes else "No.", QuestionType.DISAMBIGUATION)
        turn = math.degrees(wrap_angle(yaw_of(cx - x, cz - z) - question.state.yaw))
        side = "left" if turn > 0 else "right"
        return Reply(f"Turn {side} about {abs(round(turn))} degrees.", QuestionType.ROUTE)


def play(env: NavigationEnv, agent: Agent, max_actions: int = 700) -> list[AgentOutput]:
    """Run one episode; the actions the agent chose, in order."""
    observation, _ = env.reset(options={"episode_index": 0})
    agent.reset(env.episode_info())
    actions: list[AgentOutput] = []
    for _ in range(max_actions):
        action = agent.act(observation)
        actions.append(action)
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            break
    return actions


def make_env(
    sim: Simulator, episodes: list[Episode], task: TaskType, budget: int = 0
) -> NavigationEnv:
    oracle = ColourOracle() if task.has_dialog and budget > 0 else None
    config = TaskConfig(task=task, dialog_budget=budget)
    return NavigationEnv(episodes, config, OneScene(sim), oracle, privileged=True)
