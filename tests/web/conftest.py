"""A small served study: two episodes in a four-room house, and a server on loopback."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from vlln.sim.viewpoints import view_points
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, Goal, Instruction, ViewPoint, write_episodes
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.web.config import WebConfig
from vlln.web.server import build_server

HOUSE_SEED = 39  # four rooms, 104 objects
SCENE_ID = procedural_scene_id(HOUSE_SEED)
START_TIMEOUT = 20.0


@dataclass(frozen=True)
class Study:
    episodes: list[Episode]
    episode_file: Path
    routes: list[list[str]]  # the shortest-path follower's actions per episode, STOP last
    target_ids: list[int]


def _episodes(scenes: SceneCache) -> tuple[list[Episode], list[int]]:
    sim = scenes.get(SCENE_ID)
    grid = sim.grid
    component = grid.largest_component()
    rng = np.random.default_rng(3)
    episodes: list[Episode] = []
    targets: list[int] = []
    for inst in sim.house.instances:
        if len(episodes) == 4:
            break
        points = [p for p in view_points(grid, inst.box) if grid.component_of(*p) == component]
        if len(sim.house.instances_of(inst.category)) < 2 or not points:
            continue
        field = sim.geodesic_field(points)
        for _ in range(200):
            x, z = grid.sample_navigable_point(rng, component)
            if 2.5 < field.distance(x, z) < 5.0:
                break
        else:
            continue
        y = grid.floor_y
        goal = Goal(
            inst.box.center,
            None,
            (*inst.box.min, *inst.box.max),
            tuple(ViewPoint((px, y, pz)) for px, pz in points),
        )
        episodes.append(
            Episode(
                f"web-{len(episodes)}",
                SCENE_ID,
                (x, y, z),
                (0.0, 0.0, 0.0, 1.0),
                inst.category,
                (goal,),
                Instruction("iign", f"Search for the {inst.category}.", (str(inst.id),)),
            )
        )
        targets.append(inst.id)
    return episodes, targets


def _route(episode: Episode, scenes: SceneCache) -> list[str]:
    env = NavigationEnv([episode], TaskConfig(TaskType.IGN), scenes, privileged=True)
    observation, _ = env.reset(options={"episode_index": 0})
    actions = []
    while True:
        action = observation["expert_action"]
        actions.append(action.name)
        observation, _, terminated, truncated, _ = env.step(action)
        if terminated or truncated:
            return actions


@pytest.fixture(scope="package")
def study(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Study]:
    scenes = SceneCache()
    episodes, targets = _episodes(scenes)
    routes = [_route(episode, scenes) for episode in episodes]
    scenes.close()
    path = tmp_path_factory.mktemp("study") / "episodes.json.gz"
    write_episodes(path, episodes)
    yield Study(episodes, path, routes, targets)


@dataclass
class Served:
    url: str
    config: WebConfig


def start_server(config: WebConfig) -> tuple[str, object, threading.Thread]:
    server = build_server(config, "127.0.0.1", 0, source="test study")
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + START_TIMEOUT
    while not server.started:
        assert thread.is_alive() and time.monotonic() < deadline, "the web server did not start"
        time.sleep(0.02)
    port = server.servers[0].sockets[0].getsockname()[1]
    return f"http://127.0.0.1:{port}", server, thread


@pytest.fixture(scope="package")
def served(study: Study, tmp_path_factory: pytest.TempPathFactory) -> Iterator[Served]:
    """One server for the tests that share it; each test plays its own pairings."""
    config = WebConfig(
        episodes=tuple(study.episodes),
        out=tmp_path_factory.mktemp("web-out"),
        answer_time_limit_s=60.0,
    )
    url, server, thread = start_server(config)
    yield Served(url, config)
    server.should_exit = True  # type: ignore[attr-defined]
    thread.join(timeout=START_TIMEOUT)
