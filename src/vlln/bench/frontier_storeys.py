"""`vlln bench frontier-storeys`: the frontier agent on IIGN in houses of several storeys.

It plays what ``vlln data episodes --houses H --floors F`` followed by ``vlln eval --agent
frontier --task iign --episode-file .../test_iign.json.gz --episodes N`` plays (same episodes,
same seeds, so the same records), and splits the success rate by where the target is: on the
start's storey or on another one, and counts the episodes in which the agent reached
another storey.
"""

from __future__ import annotations

import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

from vlln.agents.frontier import FrontierAgent
from vlln.bench.figures import Figure, emit
from vlln.bench.settings import FrontierStoreysBench
from vlln.errors import ConfigError
from vlln.eval.play import derive_seed, play_episode
from vlln.eval.runner import order_by_scene, spread_over_scenes
from vlln.oracle.rule_oracle import RuleOracle
from vlln.tasks.env import NavigationEnv
from vlln.tasks.episode import Episode, read_episodes
from vlln.tasks.scenes import SceneCache
from vlln.tasks.spec import TaskConfig, TaskType
from vlln.tasks.split_files import build_split
from vlln.tasks.taxonomy import classify


@dataclass
class _Tally:
    episodes: int = 0
    successes: int = 0
    other: int = 0  # targets on another storey than the start
    other_successes: int = 0
    left: int = 0  # episodes in which the agent reached another storey


def play_frontier(scenes: SceneCache, episodes: list[Episode], seed: int) -> _Tally:
    """Play the frontier agent (truth detector, budget 5) on each IIGN episode."""
    tally = _Tally()
    config = TaskConfig(task=TaskType.IIGN, dialog_budget=5)
    for episode in episodes:
        ids = (episode.scene_id, episode.episode_id)
        agent = FrontierAgent(derive_seed(seed, "agent", *ids))
        oracle = RuleOracle(derive_seed(seed, "oracle", *ids))
        env = NavigationEnv([episode], config, scenes, oracle, privileged=True)
        record = replace(play_episode(env, agent, "frontier"), detector="truth")
        storeys = env.sim.storeys
        if storeys is None:
            raise ConfigError(f"{episode.scene_id} has one storey; ask for floors >= 2")
        start = episode.start_position[1]
        target = env.sim.house.instance(int(episode.instruction.instance_id[0])).box.min[1]
        success = classify(record) == "success"
        other = storeys.level_under(target) != storeys.level_of(start)
        tally.episodes += 1
        tally.successes += success
        tally.other += other
        tally.other_successes += other and success
        tally.left += len(agent.memory.storeys) > 1
    return tally


def run_frontier_storeys_benchmark(settings: FrontierStoreysBench) -> list[Figure]:
    """Measure and print the frontier agent's IIGN success on houses of several storeys."""
    with tempfile.TemporaryDirectory() as folder:
        build_split(
            "test",
            settings.houses,
            Path(folder),
            settings.seed,
            floors=settings.floors,
            progress=False,
        )
        source = read_episodes(Path(folder) / "test_iign.json.gz")
    chosen = order_by_scene(spread_over_scenes(source, settings.episodes))
    scenes = SceneCache(capacity=1)
    try:
        tally = play_frontier(scenes, chosen, settings.seed)
    finally:
        scenes.close()
    figures = [
        Figure("frontier_iign_episodes", float(tally.episodes), "episodes"),
        Figure("frontier_iign_success_rate", 100.0 * tally.successes / tally.episodes, "%"),
        Figure("targets_on_other_storey", float(tally.other), "episodes"),
        Figure("other_storey_successes", float(tally.other_successes), "episodes"),
        Figure("episodes_reaching_another_storey", float(tally.left), "episodes"),
    ]
    for figure in figures:
        emit(figure, settings.as_json)
    return figures
