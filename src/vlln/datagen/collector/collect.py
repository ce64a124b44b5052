"""Walking one episode with the collector: the policy acts, the triggers ask, steps are kept.

The episode's task decides the goals and the dialog. IIGN: one target, and the dialog
triggers ask the oracle. IGN: one target and no dialog: the full description is the whole
instruction, and the paper's IGN training trajectories "contain only navigation actions".
ObjectNav: every instance of the category is a goal (the episode lists them all, target
first) and there is no dialog either. ``shortest`` walks the shortest path to the nearest
goal's view point instead of exploring (:class:`CollectorPolicy` with ``explore`` off).
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Callable
from dataclasses import field
from typing import NamedTuple

import numpy as np

from vlln.config import Count, Positive, settings_dataclass
from vlln.datagen.collector.dialog import DialogConfig, DialogTriggers
from vlln.datagen.collector.ground import Ground
from vlln.datagen.collector.lattice import LatticeFollower
from vlln.datagen.collector.policy import CollectorPolicy, PolicyConfig
from vlln.datagen.trajectory import Step, Trajectory
from vlln.sim.agent import Action, AgentState
from vlln.sim.renderer import Frame
from vlln.sim.simulator import Simulator
from vlln.sim.storeys import Point3
from vlln.tasks.episode import Episode
from vlln.tasks.oracle_protocol import EpisodeContext, Oracle
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskType
from vlln.world.frame import quaternion_to_yaw
from vlln.world.model import ObjectInstance

TOO_LONG = "too_long"  # the step limit was reached before STOP


class _Goal(NamedTuple):
    key: str  # as the episode names the instance
    instance: ObjectInstance
    points: tuple[Point3, ...]  # its view points


@settings_dataclass
class CollectorConfig:
    """Everything that shapes a collected trajectory (recorded in the dataset's info)."""

    policy: PolicyConfig = field(default_factory=PolicyConfig)
    dialog: DialogConfig = field(default_factory=DialogConfig)
    goal_radius: Positive = 0.25  # the follower stops this close to a view point
    max_steps: Count = DEFAULT_MAX_STEPS


def episode_rng(seed: int, episode_id: str, stream: str) -> np.random.Generator:
    """A generator for one episode and purpose: independent of what ran before it."""
    entropy = [seed, zlib.crc32(episode_id.encode("utf-8")), zlib.crc32(stream.encode())]
    return np.random.default_rng(np.random.SeedSequence(entropy))


def collect_trajectory(
    sim: Simulator,
    episode: Episode,
    oracle: Oracle,
    seed: int = 0,
    config: CollectorConfig | None = None,
    shortest: bool = False,
    on_frame: Callable[[Frame], None] | None = None,
) -> Trajectory:
    """Walk ``episode`` in ``sim`` (its house) and return every step and dialog exchange.
    ``on_frame`` is shown each step's frame (a level view: the collector never tilts the
    camera), in step order, so a caller can keep what it needs of it instead of rendering it
    again."""
    config = config or CollectorConfig()
    house = sim.house
    state = AgentState(episode.start_position, quaternion_to_yaw(episode.start_rotation), 0.0)
    ground = Ground(sim, state.position[1])
    objectnav = episode.instruction.task_type == TaskType.OBJECTNAV
    goals = _goals(episode, ground, every=objectnav)
    field_ = ground.field([p for goal in goals for p in goal.points])  # to the nearest goal
    others: tuple[tuple[ObjectInstance, tuple[Point3, ...]], ...] = ()
    if objectnav and shortest:
        goals = [min(goals, key=lambda g: ground.distance(ground.field(g.points), state.position))]
    elif objectnav:
        others = tuple((goal.instance, goal.points) for goal in goals)
    _, target, points = goals[0]
    follower = LatticeFollower(
        ground.nav,
        field_ if others else ground.field(points),
        config.goal_radius,
        sim.config.motion,
        max_expansions=30000,
    )
    talks = episode.instruction.task_type == TaskType.IIGN
    if talks:
        told = points if sim.storeys is not None else tuple((x, z) for x, _, z in points)
        oracle.start(EpisodeContext(sim, target, told))
    observation = sim.reset(state)
    policy = CollectorPolicy(
        ground,
        target,
        points,
        follower,
        state,
        episode_rng(seed, episode.episode_id, "explore"),
        config.policy,
        others=others,
        explore=not shortest,
    )
    stated = frozenset(episode.instruction.instruction_info or ())
    triggers = DialogTriggers(
        oracle,
        house,
        target,
        stated,
        episode_rng(seed, episode.episode_id, "dialog"),
        config.dialog,
        sim.storeys,
    )
    trajectory = Trajectory(episode)
    frame = observation.frame
    if talks:
        triggers.at_start(state, frame)
    distance = math.inf
    for index in range(config.max_steps):
        distance = ground.distance(field_, state.position)
        action = policy.act(state, frame)
        if talks:
            triggers.at_frame(
                index, state, frame, distance, policy.chooser.choices, policy.seen_at is not None
            )
        if on_frame is not None:
            on_frame(frame)
        if action == Action.STOP:
            trajectory.steps.append(Step(state, action, False, distance))
            break
        observation = sim.step(action)
        trajectory.steps.append(Step(state, action, observation.collided, distance))
        state, frame = observation.state, observation.frame
    else:
        trajectory.failure = TOO_LONG
    trajectory.failure = trajectory.failure or policy.failure
    trajectory.dialog = triggers.finish(distance)
    trajectory.target = next(g.key for g in goals if g.instance.id == policy.target.id)
    return trajectory


def _goals(episode: Episode, ground: Ground, every: bool) -> list[_Goal]:
    """The episode's goal instances with their view points: the target alone, or (``every``)
    each goal the episode lists that has view points, in its order (ids and goals are listed
    alike). An ObjectNav episode lists every instance of its category, some with no view
    point to walk to; aiming at one would leave the walk without a goal."""
    house = ground.sim.house
    pairs = list(zip(episode.instruction.instance_id, episode.goals, strict=False))
    if every:
        pairs = [(key, goal) for key, goal in pairs if goal.view_points]
    return [
        _Goal(
            key,
            house.instance_for_key(key),
            tuple(ground.point(v.position) for v in goal.view_points),
        )
        for key, goal in (pairs if every else pairs[:1])
    ]
