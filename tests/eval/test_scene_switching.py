"""Runs that move from house to house: leaving a house must not change any later line."""

from __future__ import annotations

import pytest

from tests.eval.runs import lines
from vlln.eval.config import EvalConfig
from vlln.eval.runner import load_episodes, run_evaluation
from vlln.tasks.episode import Episode, write_episodes


@pytest.mark.slow
def test_moving_through_houses_changes_no_episode_line(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    """Three houses in one run: the third house's lines equal those of a run on it alone."""
    cache = tmp_path_factory.mktemp("three_houses")
    three = EvalConfig(agent="random", task="iign", houses=3, preset="small")
    by_scene: dict[str, list[Episode]] = {}
    for episode in load_episodes(three, cache, progress=False):
        by_scene.setdefault(episode.scene_id, []).append(episode)
    first, second, third = by_scene.values()
    files = {"all": [first[0], second[0], *third[:2]], "third": third[:2]}
    results = {}
    for name, chosen in files.items():
        path = cache / f"{name}.json.gz"
        write_episodes(path, chosen)
        config = EvalConfig(
            agent="expert", task="iign", split=None, episode_file=str(path), budgets=(0,)
        )
        run_evaluation(config, cache / name, progress=False)
        results[name] = lines(cache / name)
    assert len(results["all"]) == 4
    assert results["all"][2:] == results["third"]
    assert all('"end_reason":"stop"' in line for line in results["all"])
