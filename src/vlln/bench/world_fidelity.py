"""How a preset's test houses and episodes compare with Matterport3D as VL-LN uses it.

The figures are measured on the houses and episodes the benchmark really plays: the test
split's houses of the preset, with the episodes :func:`~vlln.tasks.split_files.build_split`
writes for them (same seed, same settings). Each is printed beside its anchor
(:mod:`vlln.bench.anchors`), so a generator change that drifts away from the paper's scenes
shows at once.
"""

from __future__ import annotations

import json
import statistics
from collections import Counter
from dataclasses import dataclass

from vlln.bench.anchors import compare
from vlln.tasks.generation import episode_config, generate_house_episodes, house_rng
from vlln.tasks.scenes import SceneCache, procedural_scene_id
from vlln.tasks.splits import SPLIT_SIZES, TEST_PROTOCOL_EPISODES, house_seeds


@dataclass(frozen=True)
class HouseFigures:
    """One house's statistics in the anchors' terms."""

    regions: int
    floors: int
    navigable_area_m2: float
    instances: int
    instances_per_category: float
    episodes: int
    with_distractor: int  # episodes whose target shares its category with another instance
    distractors: int  # same-category others of the targets, summed over the episodes
    start_distance_sum: float
    start_poses: int  # distinct start positions among the episodes


def house_figures(preset: str, seed: int, scenes: SceneCache) -> HouseFigures:
    """Build house ``seed`` of ``preset`` and its episodes, and measure both."""
    sim = scenes.get(procedural_scene_id(seed, 1, preset))
    house = sim.house
    made = generate_house_episodes(sim, house_rng(0, seed), episode_config(preset))
    counts = Counter(inst.category for inst in house.instances)
    area = sim.storeys.navigable_area if sim.storeys is not None else sim.grid.navigable_area
    return HouseFigures(
        regions=len(house.rooms),
        floors=len({room.level for room in house.rooms}) or 1,
        navigable_area_m2=float(area),
        instances=len(house.instances),
        instances_per_category=statistics.mean(counts.values()) if counts else 0.0,
        episodes=len(made.iign),
        with_distractor=sum(1 for ep in made.objectnav if len(ep.goals) > 1),
        distractors=sum(len(ep.goals) - 1 for ep in made.objectnav),
        start_distance_sum=sum(float(ep.info["geodesic_distance"]) for ep in made.iign),
        start_poses=len({tuple(ep.start_position) for ep in made.iign}),
    )


def preset_statistics(preset: str, houses: int | None = None) -> dict[str, float]:
    """The anchors' statistics over the first ``houses`` test houses of ``preset``."""
    count = SPLIT_SIZES["test"] if houses is None else houses
    scenes = SceneCache(capacity=1)
    try:
        rows = [house_figures(preset, seed, scenes) for seed in house_seeds("test", count)]
    finally:
        scenes.close()
    episodes = sum(r.episodes for r in rows)
    return {
        "regions_per_building": statistics.mean(r.regions for r in rows),
        "navigable_area_m2": statistics.mean(r.navigable_area_m2 for r in rows),
        "floors_per_building": statistics.mean(r.floors for r in rows),
        "instances_per_scene": statistics.mean(r.instances for r in rows),
        "instances_per_category": statistics.mean(r.instances_per_category for r in rows),
        "distractor_share": sum(r.with_distractor for r in rows) / max(episodes, 1),
        "distractors_per_target": sum(r.distractors for r in rows) / max(episodes, 1),
        "start_to_target_geodesic_m": sum(r.start_distance_sum for r in rows) / max(episodes, 1),
        "start_poses_per_scene": statistics.mean(r.start_poses for r in rows),
        "test_episodes": float(min(TEST_PROTOCOL_EPISODES, episodes)),
        "test_scenes": float(count),
    }


def print_comparison(measured: dict[str, float], as_json: bool) -> list[dict[str, object]]:
    """Each statistic beside its anchor: one JSON object per line, or an aligned table."""
    rows = compare(measured)
    for row in rows:
        if as_json:
            print(json.dumps(row))
            continue
        value = row["measured"]
        shown = "-" if value is None else f"{float(value):.2f}"  # type: ignore[arg-type]
        verdict = {True: "within", False: "OUTSIDE", None: ""}[row["within"]]  # type: ignore[index]
        print(
            f"{row['name']:<28} {shown:>9}  anchor {row['anchor']:>7} "
            f"[{row['low']}, {row['high']}] {row['unit']}  {verdict}"
        )
    return rows
