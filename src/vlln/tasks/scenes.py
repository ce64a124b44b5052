"""Scene ids and the simulators behind them.

Procedural houses are named ``vlln/house_<seed>/house_<seed>.glb`` in episode files, the shape
of the released data's paths to scans (``<root>/<scene>/<scene>.glb``, whose folder the
reference reads as the scene); the short ``vlln/house_<seed>`` of older files is read too.
Other scene ids name an imported scan: the folder ``<scenes dir>/<scene>`` (see
:mod:`vlln.world.scans`); an exported scan's episodes name it as habitat names Matterport3D
scans, ``<style>/<scene>/<scene>.glb`` (:func:`scan_scene_id`). A procedural scene id is never
read from a scenes folder: with one given, that is said once. :class:`SceneCache`
builds a simulator per scene and keeps the most recent few, since runners visit episodes
scene by scene.
"""

from __future__ import annotations

import logging
import re
from collections import OrderedDict
from pathlib import Path

from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator, SimulatorConfig
from vlln.tasks.episode import scene_name
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.model import House
from vlln.world.scans import load_scene

_PROCEDURAL = re.compile(
    r"^vlln/house_([0-9]{1,12})(_[23]f)?(?:/house_\1(?(2)\2)\.glb)?$", re.ASCII
)
MAX_SEED = 999_999_999
"""The largest house seed a scene id may name."""
logger = logging.getLogger(__name__)


def procedural_scene_id(seed: int, floors: int = 1) -> str:
    """``vlln/house_<seed>/house_<seed>.glb``; a house of 2 or 3 storeys (a different house
    for the same seed) adds ``_2f`` or ``_3f`` to the name."""
    name = f"house_{seed:05d}" if floors == 1 else f"house_{seed:05d}_{floors}f"
    return f"vlln/{name}/{name}.glb"


def scan_scene_id(style: str, name: str) -> str:
    """``<style>/<name>/<name>.glb``: a scan's scene id, as the reference's Matterport3D
    episodes write ``mp3d/<scan>/<scan>.glb``; ``--scenes`` is the folder holding ``<name>/``."""
    return f"{style}/{name}/{name}.glb"


def scene_house(scene_id: str, scenes_dir: str | Path | None = None) -> House:
    """The house a scene id names: a procedural house, or the scan ``<scenes_dir>/<scene>``."""
    if is_procedural(scene_id):
        return procedural_house(scene_id)
    if scenes_dir is None:
        raise ConfigError(
            f"scene {scene_id[:80]!r} is a scanned scene; pass the folder of scanned scenes "
            f"that holds {scene_name(scene_id)}/ (--scenes DIR)"
        )
    return load_scene(Path(scenes_dir) / scene_name(scene_id))


def house_scene_id(house: House) -> str:
    """The scene id of a procedural house, storeys included."""
    if house.seed is None:
        raise ConfigError(f"house {house.name!r} is not a procedural house (it has no seed)")
    return procedural_scene_id(house.seed, len({room.level for room in house.rooms}) or 1)


def procedural_floors(scene_id: str) -> int:
    """How many storeys the procedural house of a scene id has."""
    procedural_seed(scene_id)
    match = _PROCEDURAL.match(scene_id)
    suffix = match.group(2) if match is not None else None
    return 1 if not suffix else int(suffix[1])


def is_procedural(scene_id: str) -> bool:
    return _PROCEDURAL.match(scene_id) is not None


def procedural_seed(scene_id: str) -> int:
    """The house seed a scene id names (ASCII digits, at most :data:`MAX_SEED`)."""
    match = _PROCEDURAL.match(scene_id)
    if match is None:
        raise ConfigError(
            f"scene {scene_id[:80]!r} is not a built-in procedural house "
            "(vlln/house_<seed>/house_<seed>.glb, ASCII digits); pass the folder of imported "
            "scenes (--scenes)"
        )
    seed = int(match.group(1))
    if seed > MAX_SEED:
        raise ConfigError(f"scene {scene_id!r} names seed {seed}; seeds are at most {MAX_SEED}")
    return seed


def procedural_house(scene_id: str) -> House:
    """The procedural house a scene id names, with its storeys (``_2f`` is another house
    than the one-storey house of the same seed)."""
    return generate_house(
        procedural_seed(scene_id), HouseParameters(floors=procedural_floors(scene_id))
    )


def canonical_seed(scene_id: str) -> int:
    """:func:`procedural_seed` of a scene id in its one spelling, :func:`procedural_scene_id`;
    ``vlln/house_76`` and ``vlln/house_076`` are refused, naming ``vlln/house_00076``."""
    seed = procedural_seed(scene_id)
    spelled = procedural_scene_id(seed, procedural_floors(scene_id))
    if scene_id != spelled:
        raise ConfigError(f"scene {scene_id!r} is spelled {spelled!r}; each house has one id")
    return seed


class SceneCache:
    """Simulators by scene id, least recently used dropped first."""

    def __init__(
        self,
        config: SimulatorConfig | None = None,
        capacity: int = 2,
        scenes_dir: str | Path | None = None,
    ) -> None:
        self.config = config
        self.capacity = capacity
        self.scenes_dir = None if scenes_dir is None else Path(scenes_dir)
        self._sims: OrderedDict[str, Simulator] = OrderedDict()
        self._told = False  # whether it said that procedural scenes ignore scenes_dir

    def get(self, scene_id: str) -> Simulator:
        sim = self._sims.get(scene_id)
        if sim is not None:
            self._sims.move_to_end(scene_id)
            return sim
        sim = Simulator(self._house(scene_id), self.config)
        self._sims[scene_id] = sim
        while len(self._sims) > self.capacity:
            _, old = self._sims.popitem(last=False)
            old.close()
        return sim

    def _house(self, scene_id: str) -> House:
        if self.scenes_dir is not None and is_procedural(scene_id) and not self._told:
            self._told = True
            logger.warning(
                "%s names a procedural house: it and any other vlln/house_... scene are "
                "generated, not read from --scenes %s (episodes of an exported scan name "
                "mp3d/<scene>/<scene>.glb; vlln world export --episodes writes them)",
                scene_id,
                self.scenes_dir,
            )
        return scene_house(scene_id, self.scenes_dir)

    def holds(self, scene_id: str) -> bool:
        """Whether the scene's simulator is built and kept (getting it builds nothing)."""
        return scene_id in self._sims

    def holds_simulator(self, sim: Simulator) -> bool:
        """Whether ``sim`` is still one of the kept simulators (not dropped and closed)."""
        return any(kept is sim for kept in self._sims.values())

    def close(self) -> None:
        for sim in self._sims.values():
            sim.close()
        self._sims.clear()
