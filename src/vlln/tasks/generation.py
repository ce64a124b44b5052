"""Episodes for the built-in procedural houses: IIGN, IGN and ObjectNav, aligned one to one.

Every instance of a house is tried as a target. Its goal is its box with view points (navigable
cells in the box grown by 0.6 m, every ``view_point_stride``-th grid row and column) on the
house's main floor, its largest navigable component. A target is skipped, and counted by
reason, with too few view points, with none on the main floor, when no full instruction
singles it out (:class:`AmbiguousTargetError`), or when no start lies in the distance range.

Starts come from a pool drawn per house on the main floor, as the paper pairs about 42 start
poses per scene with its targets: one multi-source Dijkstra from the pool gives the distance
from every start to every cell, so a target's distances to all starts are one array look-up
instead of a geodesic field per target. A start qualifies when its distance to the target's
view points is within ``[min_start_distance, max_start_distance]`` and no instance of the
category is nearer than ``min_start_distance`` (so ObjectNav is not solved at the start).

Element ``i`` of the three lists has the same target, start and ``episode_id``
(``"<house seed>_<target id>_<start index>"``). IIGN states only the category
(``instruction_info`` null), IGN the full instruction and its attributes; ObjectNav's goals are
every instance of the category, the target first. Each episode's ``info`` holds its
``geodesic_distance`` from the start to the nearest goal view point.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from typing import Annotated, Any, Self

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator
from scipy.sparse import csgraph

from vlln.config import Count, settings_dataclass
from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator
from vlln.sim.storeys import Point3
from vlln.sim.viewpoints import storey_view_points, view_points
from vlln.tasks.episode import (
    Episode,
    Goal,
    Instruction,
    ViewPoint,
)
from vlln.tasks.instructions import AmbiguousTargetError, InstructionWriter, partial_instruction
from vlln.tasks.scenes import house_scene_id
from vlln.tasks.spec import TaskType
from vlln.world.frame import yaw_to_quaternion
from vlln.world.generator.presets import SMALL
from vlln.world.model import ObjectInstance

# Why a target gave no episodes, in the order the checks run.
TOO_FEW_VIEW_POINTS = "too_few_view_points"
UNREACHABLE = "unreachable"
AMBIGUOUS_INSTRUCTION = "ambiguous_instruction"
NO_START_IN_RANGE = "no_start_in_range"
SKIP_REASONS = (TOO_FEW_VIEW_POINTS, UNREACHABLE, AMBIGUOUS_INSTRUCTION, NO_START_IN_RANGE)

# Starts keep this distance (m) inside the range, so that a distance recomputed from the goal
# side (other summation order, GeodesicField's round-up) still lies within it.
_RANGE_TOLERANCE = 1e-6


Metres = Annotated[float, Field(ge=0.0, allow_inf_nan=False)]


@settings_dataclass
class EpisodeGenConfig:
    """How many episodes per target and which start poses and view points qualify."""

    starts_per_target: Count = 1
    min_start_distance: Metres = 1.5  # geodesic metres from the start to the nearest view point
    max_start_distance: Metres = 30.0
    view_point_stride: Count = 2  # keep every n-th grid row and column of view points
    min_view_points: Count = 1  # fewer reachable view points: the target is skipped
    targets_per_house: Annotated[int, Field(ge=0)] | None = None  # None: every usable instance
    start_pool_size: Count = 42  # start poses drawn per house (the paper's mean per scene)

    @model_validator(mode="after")
    def _consistent(self) -> Self:
        low, high = self.min_start_distance, self.max_start_distance
        if not low < high:
            raise ConfigError(f"need min_start_distance < max_start_distance, got {low}, {high}")
        if self.start_pool_size < self.starts_per_target:
            raise ConfigError(
                f"start_pool_size ({self.start_pool_size}) must be at least starts_per_target "
                f"({self.starts_per_target})"
            )
        return self


def episode_config(preset: str) -> EpisodeGenConfig:
    """The episode settings of a preset's splits. ``mp3d`` houses keep every fourth grid row
    and column of view points (0.2 m apart): a navigable point of a grown box then lies within
    0.15 m of a view point, well inside the 0.25 m success radius, while an ObjectNav episode,
    which lists the view points of every instance of its category, stays a few hundred points
    long instead of thousands (a 14-house test split reads in seconds, in well under 1 GB)."""
    if preset == SMALL.name:
        return EpisodeGenConfig()
    return EpisodeGenConfig(view_point_stride=4, min_start_distance=3.0, max_start_distance=45.0)


@dataclass
class HouseStats:
    """What one house gave: episodes per task, skipped targets by reason, distractors."""

    house_seed: int
    scene_id: str
    instances: int
    targets: int = 0  # instances tried as targets
    used: int = 0  # targets with episodes
    episodes: int = 0  # per task (the three lists are aligned)
    skipped: dict[str, int] = field(default_factory=lambda: dict.fromkeys(SKIP_REASONS, 0))
    distractors: Counter[int] = field(default_factory=Counter)  # same-category others -> targets
    episodes_per_category: Counter[str] = field(default_factory=Counter)
    start_distance_sum: float = 0.0  # geodesic start-to-target metres over the episodes

    def add(self, other: HouseStats) -> None:
        """Add another house's counts (for split totals)."""
        for name in ("instances", "targets", "used", "episodes", "start_distance_sum"):
            setattr(self, name, getattr(self, name) + getattr(other, name))
        for reason, count in other.skipped.items():
            self.skipped[reason] += count
        self.distractors.update(other.distractors)
        self.episodes_per_category.update(other.episodes_per_category)

    def counts_json(self) -> dict[str, Any]:
        """The counts as JSON (without the house's seed and scene id)."""
        return {
            "instances": self.instances,
            "targets": self.targets,
            "targets_used": self.used,
            "episodes": self.episodes,
            "skipped": dict(self.skipped),
            "distractors_per_target": {str(k): v for k, v in sorted(self.distractors.items())},
            "episodes_per_category": dict(sorted(self.episodes_per_category.items())),
            "mean_start_distance": round(self.start_distance_sum / max(self.episodes, 1), 4),
        }

    def to_json(self) -> dict[str, Any]:
        return {"house_seed": self.house_seed, "scene_id": self.scene_id, **self.counts_json()}


@dataclass(frozen=True)
class HouseEpisodes:
    """One house's episodes, aligned across the three tasks, and its statistics."""

    iign: list[Episode]
    ign: list[Episode]
    objectnav: list[Episode]
    stats: HouseStats

    def of_task(self, task: TaskType) -> list[Episode]:
        return {TaskType.IIGN: self.iign, TaskType.IGN: self.ign}.get(task, self.objectnav)


@dataclass(frozen=True)
class _Site:
    """An instance's goal record and the flat grid cells of its view points on the main floor."""

    goal: Goal
    cells: NDArray[np.intp]
    navigable_view_points: int  # including those off the main floor


_Triple = tuple[Episode, Episode, Episode]  # IIGN, IGN, ObjectNav with one target and start


def generate_house_episodes(
    sim: Simulator, rng: np.random.Generator, config: EpisodeGenConfig | None = None
) -> HouseEpisodes:
    """IIGN, IGN and ObjectNav episodes for every usable target of the simulator's house."""
    config = config or EpisodeGenConfig()
    house = sim.house
    if house.seed is None:
        raise ConfigError(
            f"house {house.name!r} has no seed; episodes are generated for procedural houses "
            "made by vlln.world.generator.generate_house"
        )
    stats = HouseStats(house.seed, house_scene_id(house), len(house.instances))
    if sim.storeys is None and not sim.grid.navigable.any():
        return HouseEpisodes([], [], [], stats)
    context = _HouseContext(sim, rng, config)
    targets = sorted(house.instances, key=lambda inst: inst.id)
    if config.targets_per_house is not None:
        targets = [targets[int(i)] for i in rng.permutation(len(targets))]
    triples: list[_Triple] = []
    for target in targets:
        if stats.used == config.targets_per_house:
            break
        stats.targets += 1
        made = context.target_episodes(target)
        if isinstance(made, str):
            stats.skipped[made] += 1
            continue
        stats.used += 1
        stats.distractors[len(made[0][2].goals) - 1] += 1
        stats.episodes += len(made)
        stats.episodes_per_category[target.category] += len(made)
        stats.start_distance_sum += sum(t[0].info["geodesic_distance"] for t in made)
        triples.extend(made)
    triples.sort(key=lambda triple: _id_order(triple[0].episode_id))
    iign, ign, objectnav = ([t[i] for t in triples] for i in range(3))
    return HouseEpisodes(iign, ign, objectnav, stats)


class _HouseContext:
    """One house's start pool, instruction writer and goal records, shared by its targets.

    With several storeys, starts and view points lie on every storey of the main walkable
    structure, so a target is often on another storey than the start.
    """

    def __init__(self, sim: Simulator, rng: np.random.Generator, config: EpisodeGenConfig) -> None:
        self.house, self.rng, self.config = sim.house, rng, config
        self.storeys = sim.storeys
        self.scene_id = house_scene_id(self.house)
        self.writer = InstructionWriter(self.house)
        self._sites: dict[int, _Site] = {}
        self.starts: list[Point3]
        if self.storeys is not None:
            self.main_floor = self.storeys.largest_component()
            self.starts = [
                self.storeys.sample_navigable_point(rng, self.main_floor)
                for _ in range(config.start_pool_size)
            ]
            graph = self.storeys.cell_graph()
        else:
            self.grid = sim.grid
            self.main_floor = self.grid.largest_component()
            self.starts = [
                (x, self.grid.floor_y, z)
                for x, z in (
                    self.grid.sample_navigable_point(rng, self.main_floor)
                    for _ in range(config.start_pool_size)
                )
            ]
            graph = self.grid.cell_graph()
        # Row i: geodesic distance from start i to every cell (the cell graph is symmetric).
        self.start_distances: NDArray[np.float64] = csgraph.dijkstra(
            graph, directed=True, indices=[self._node(p) for p in self.starts]
        )

    def _node(self, point: Point3) -> int:
        if self.storeys is not None:
            return self.storeys.node(*point)
        row, col = self.grid.world_to_cell(point[0], point[2])
        return row * self.grid.shape[1] + col

    def distance_to(self, cells: NDArray[np.intp]) -> NDArray[np.float64]:
        """Per start, the geodesic distance to the nearest of ``cells`` (``inf``: none)."""
        if cells.size == 0:
            return np.full(len(self.starts), math.inf)
        nearest: NDArray[np.float64] = self.start_distances[:, cells].min(axis=1)
        return nearest

    def site(self, instance: ObjectInstance) -> _Site:
        """The instance's goal, with its view points on the main floor (built once)."""
        if instance.id not in self._sites:
            box, stride = instance.box, self.config.view_point_stride
            points: list[Point3]
            if self.storeys is not None:
                points = storey_view_points(self.storeys, box, stride=stride)
                labels = self.storeys.components()[0]
                kept = [p for p in points if labels[self._node(p)] == self.main_floor]
            else:
                grid = self.grid
                points = [(x, grid.floor_y, z) for x, z in view_points(grid, box, stride=stride)]
                plan_labels = grid.components()[0]
                kept = [
                    p
                    for p in points
                    if plan_labels[grid.world_to_cell(p[0], p[2])] == self.main_floor
                ]
            goal = Goal(
                position=box.center,
                radius=None,
                bbox=(*box.min, *box.max),
                view_points=tuple(ViewPoint(p) for p in kept),
            )
            cells = np.array([self._node(p) for p in kept], dtype=np.intp)
            self._sites[instance.id] = _Site(goal, cells, len(points))
        return self._sites[instance.id]

    def target_episodes(self, target: ObjectInstance) -> list[_Triple] | str:
        """The target's episodes, or the reason (one of :data:`SKIP_REASONS`) it has none."""
        config, rng = self.config, self.rng
        own = self.site(target)
        if own.navigable_view_points < config.min_view_points:
            return TOO_FEW_VIEW_POINTS
        if own.cells.size < config.min_view_points:
            return UNREACHABLE
        try:
            full = self.writer.full_instruction(target.id, rng)
        except AmbiguousTargetError:
            return AMBIGUOUS_INSTRUCTION
        others = sorted(
            (i for i in self.house.instances_of(target.category) if i.id != target.id),
            key=lambda inst: inst.id,
        )
        category = [own, *(self.site(i) for i in others)]
        to_target = self.distance_to(own.cells)
        to_category = self.distance_to(np.concatenate([s.cells for s in category]))
        low = config.min_start_distance + _RANGE_TOLERANCE
        high = config.max_start_distance - _RANGE_TOLERANCE
        eligible = np.flatnonzero((to_target >= low) & (to_target <= high) & (to_category >= low))
        if eligible.size == 0:
            return NO_START_IN_RANGE
        count = min(config.starts_per_target, eligible.size)
        chosen = np.sort(rng.choice(eligible, size=count, replace=False))
        ids = (str(target.id),)
        partial = partial_instruction(target.category)
        every_id = (*ids, *(str(i.id) for i in others))
        instructions = (
            Instruction(TaskType.IIGN.value, partial, ids, None),
            Instruction(TaskType.IGN.value, full.text, ids, tuple(full.instruction_info)),
            Instruction(TaskType.OBJECTNAV.value, partial, every_id, None),
        )
        goals = ((own.goal,), (own.goal,), tuple(s.goal for s in category))
        made: list[_Triple] = []
        for k, start in enumerate(chosen.tolist()):
            qx, qy, qz, qw = yaw_to_quaternion(float(rng.uniform(-math.pi, math.pi)))
            distances = (to_target[start], to_target[start], to_category[start])
            iign, ign, objectnav = (
                Episode(
                    episode_id=episode_id(int(self.house.seed or 0), target.id, k),
                    scene_id=self.scene_id,
                    start_position=self.starts[start],
                    start_rotation=(qx, qy, qz, qw),
                    object_category=target.category,
                    goals=goals[i],
                    instruction=instructions[i],
                    info={"geodesic_distance": round(float(distances[i]), 4)},
                )
                for i in range(3)
            )
            made.append((iign, ign, objectnav))
        return made


_TARGETS_PER_HOUSE = 10_000
_STARTS_PER_TARGET = 100


def episode_id(house_seed: int, target_id: int, start: int) -> str:
    """A decimal id unique per file (the reference evaluator reads ids with ``int()``):
    ``<seed><target, 4 digits><start, 2 digits>``, so ids sort by house, target, then start."""
    if not (0 <= target_id < _TARGETS_PER_HOUSE and 0 <= start < _STARTS_PER_TARGET):
        raise ConfigError(
            f"episode ids hold target ids below {_TARGETS_PER_HOUSE} and fewer than "
            f"{_STARTS_PER_TARGET} starts per target; got target {target_id}, start {start}"
        )
    return str((house_seed * _TARGETS_PER_HOUSE + target_id) * _STARTS_PER_TARGET + start)


def _id_order(episode_id: str) -> int:
    return int(episode_id)


def check_count(name: str, value: object, low: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise ConfigError(f"{name} must be a whole number >= {low}, got {value!r}")


def house_rng(rng_seed: int, house_seed: int) -> np.random.Generator:
    """The generator of one house's episodes: adding houses leaves earlier houses unchanged."""
    return np.random.default_rng(np.random.SeedSequence([rng_seed, house_seed]))
