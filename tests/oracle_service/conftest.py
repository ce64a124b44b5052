"""A small served world shared by the service tests: one house, one target, navigable poses."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from vlln.sim.simulator import Simulator
from vlln.sim.viewpoints import view_points
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint
from vlln.tasks.scenes import SceneCache, procedural_scene_id

SCENE_ID = procedural_scene_id(76)
TOKEN = "test-token-0123456789"


@dataclass(frozen=True)
class World:
    """What a client needs to know about the served house."""

    scene_id: str
    target_id: int
    target_category: str
    target_color: str
    poses: list[dict[str, Any]]  # on the navigable floor
    floor_y: float
    episode: Episode
    instance_ids: list[int]
    sim: Simulator  # the same house, for answers computed in-process
    view_points: list[tuple[float, float]]


@pytest.fixture(scope="package")
def world() -> Iterator[World]:
    cache = SceneCache()
    sim = cache.get(SCENE_ID)
    grid = sim.grid
    component = grid.largest_component()
    target = next(
        inst
        for inst in sim.house.instances
        if inst.attributes.color
        and any(grid.component_of(*p) == component for p in view_points(grid, inst.box))
    )
    points = view_points(grid, target.box)
    rng = np.random.default_rng(5)
    starts = [grid.sample_navigable_point(rng, component) for _ in range(4)]
    poses: list[dict[str, Any]] = [
        {"position": [x, grid.floor_y, z], "yaw": 0.5 * i, "tilt": 0.0}
        for i, (x, z) in enumerate(starts)
    ]
    episode = Episode(
        episode_id="ep-1",
        scene_id=SCENE_ID,
        start_position=(starts[0][0], grid.floor_y, starts[0][1]),
        start_rotation=(0.0, 0.0, 0.0, 1.0),  # yaw 0
        object_category=target.category,
        goals=(
            Goal(
                position=target.box.center,
                radius=None,
                bbox=(*target.box.min, *target.box.max),
                view_points=tuple(ViewPoint((x, grid.floor_y, z)) for x, z in points),
            ),
        ),
        instruction=Instruction("iign", f"Search for the {target.category}.", (str(target.id),)),
    )
    yield World(
        scene_id=SCENE_ID,
        target_id=target.id,
        target_category=target.category,
        target_color=target.attributes.color,
        poses=poses,
        floor_y=grid.floor_y,
        episode=episode,
        instance_ids=[inst.id for inst in sim.house.instances],
        sim=sim,
        view_points=points,
    )
    cache.close()
