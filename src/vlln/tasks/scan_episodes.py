"""Episode files for an exported scan: the house's episodes, naming the scan, not the house.

``vlln world export --episodes`` writes a procedural house as a scanned scene and its IIGN,
IGN and ObjectNav episodes beside it. Their scene id is the scan's,
``<style>/<scene>/<scene>.glb`` (as the reference names ``mp3d/<scan>/<scan>.glb``), so that
``vlln eval --episode-file FILE --scenes <out>/<style>`` plays them on the imported scan. The
episodes are made on the house itself; exported and imported back, the scan has the same
instances and the same navigable grid (``tests/world/test_scan_storeys.py``).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from vlln.sim.simulator import Simulator
from vlln.tasks.episode import write_episodes
from vlln.tasks.generation import EpisodeGenConfig, generate_house_episodes, house_rng
from vlln.tasks.scenes import scan_scene_id
from vlln.tasks.spec import TaskType
from vlln.world.model import House


def scan_episode_path(scene_dir: Path, task: TaskType) -> Path:
    """``<scenes>/<scene>_<task>.json.gz``, beside the scene folder."""
    return scene_dir.parent / f"{scene_dir.name}_{task.value}.json.gz"


def write_scan_episodes(
    house: House,
    scene_dir: Path,
    style: str,
    rng_seed: int = 0,
    config: EpisodeGenConfig | None = None,
) -> list[Path]:
    """Write the episodes of ``house`` for its exported scene folder ``scene_dir`` of
    ``style``; returns the files (one per task)."""
    with Simulator(house) as sim:
        made = generate_house_episodes(sim, house_rng(rng_seed, house.seed or 0), config)
    scene_id = scan_scene_id(style, scene_dir.name)
    paths = []
    for task in TaskType:
        path = scan_episode_path(scene_dir, task)
        write_episodes(path, [replace(e, scene_id=scene_id) for e in made.of_task(task)])
        paths.append(path)
    return paths
