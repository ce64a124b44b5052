"""The anchored statistics are measured on the houses and episodes the benchmark plays."""

from __future__ import annotations

import pytest

from vlln.bench.world_fidelity import preset_statistics, print_comparison
from vlln.tasks.generation import episode_config, generate_house_episodes, house_rng
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.splits import house_seeds


@pytest.mark.slow
def test_statistics_of_one_small_house_match_its_episodes(capsys) -> None:  # type: ignore[no-untyped-def]
    measured = preset_statistics("small", houses=1)
    seed = house_seeds("test", 1)[0]
    scenes = SceneCache(capacity=1)
    try:
        sim = scenes.get(procedural_scene_id(seed))
        made = generate_house_episodes(sim, house_rng(0, seed), episode_config("small"))
        house = sim.house
    finally:
        scenes.close()
    assert measured["floors_per_building"] == 1.0
    assert measured["regions_per_building"] == len(house.rooms)
    assert measured["instances_per_scene"] == len(house.instances)
    with_distractor = sum(len(ep.goals) > 1 for ep in made.objectnav) / len(made.objectnav)
    assert measured["distractor_share"] == with_distractor
    assert 0.0 < measured["navigable_area_m2"] < 250.0
    rows = print_comparison(measured, as_json=False)
    out = capsys.readouterr().out
    assert "regions_per_building" in out and ("OUTSIDE" in out or "within" in out)
    assert {row["name"] for row in rows} >= {"distractor_share", "start_to_target_geodesic_m"}
