"""Scene ids and the simulators behind them.

Procedural houses are named ``vlln/house_<seed>/house_<seed>.glb`` in episode files, the shape
of the released data's paths to scans (``<root>/<scene>/<scene>.glb``, whose folder the
reference reads as the scene); the short ``vlln/house_<seed>`` of older files is read too.
Houses of the ``mp3d`` preset (:mod:`vlln.world.generator.presets`) are
``vlln/mp3d_<seed>/mp3d_<seed>.glb``; their storeys follow from the seed.
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
from collections.abc import Callable
from pathlib import Path

from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator, SimulatorConfig
from vlln.tasks.episode import scene_name
from vlln.world.generator.presets import SMALL, generate_preset_house, house_name
from vlln.world.model import House
from vlln.world.scans import load_scene

_PROCEDURAL = re.compile(
    r"^vlln/(?P<kind>house|mp3d)_(?P<seed>[0-9]{1,12})(?P<floors>_[23]f)?"
    r"(?:/(?P=kind)_(?P=seed)(?(floors)(?P=floors))\.glb)?$",
    re.ASCII,
)
MAX_SEED = 999_999_999
"""The largest house seed a scene id may name."""
logger = logging.getLogger(__name__)


def procedural_scene_id(seed: int, floors: int = 1, preset: str = SMALL.name) -> str:
    """``vlln/house_<seed>/house_<seed>.glb``; a house of 2 or 3 storeys (a different house
    for the same seed) adds ``_2f`` or ``_3f`` to the name. A house of another preset is
    ``vlln/<preset>_<seed>/<preset>_<seed>.glb`` (its storeys follow from the seed)."""
    name = house_name(preset, seed, floors)
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
    """The scene id of a procedural house, storeys and preset included."""
    if house.seed is None or not is_procedural(f"vlln/{house.name}"):
        raise ConfigError(f"house {house.name!r} is not a procedural house (it has no seed)")
    return f"vlln/{house.name}/{house.name}.glb"


def _match(scene_id: str) -> re.Match[str]:
    match = _PROCEDURAL.match(scene_id)
    if match is None or (match.group("kind") != "house" and match.group("floors")):
        raise ConfigError(
            f"scene {scene_id[:80]!r} is not a built-in procedural house "
            "(vlln/house_<seed>/house_<seed>.glb or vlln/mp3d_<seed>/mp3d_<seed>.glb, ASCII "
            "digits); pass the folder of imported scenes (--scenes)"
        )
    return match


def procedural_floors(scene_id: str) -> int | None:
    """How many storeys a ``house_`` scene id names; ``None`` for a preset whose storeys
    follow from the seed."""
    match = _match(scene_id)
    procedural_seed(scene_id)
    if match.group("kind") != "house":
        return None
    suffix = match.group("floors")
    return 1 if not suffix else int(suffix[1])


def procedural_preset(scene_id: str) -> str:
    """The house preset a procedural scene id names (``house_`` ids are ``small``)."""
    kind = _match(scene_id).group("kind")
    return SMALL.name if kind == "house" else kind


def is_procedural(scene_id: str) -> bool:
    try:
        _match(scene_id)
    except ConfigError:
        return False
    return True


def procedural_seed(scene_id: str) -> int:
    """The house seed a scene id names (ASCII digits, at most :data:`MAX_SEED`)."""
    seed = int(_match(scene_id).group("seed"))
    if seed > MAX_SEED:
        raise ConfigError(f"scene {scene_id!r} names seed {seed}; seeds are at most {MAX_SEED}")
    return seed


def procedural_house(scene_id: str) -> House:
    """The procedural house a scene id names, with its storeys (``_2f`` is another house
    than the one-storey house of the same seed) and preset."""
    return generate_preset_house(
        procedural_seed(scene_id), procedural_preset(scene_id), procedural_floors(scene_id)
    )


def canonical_seed(scene_id: str) -> int:
    """:func:`procedural_seed` of a scene id in its one spelling, :func:`procedural_scene_id`;
    ``vlln/house_76`` and ``vlln/house_076`` are refused, naming ``vlln/house_00076``."""
    seed = procedural_seed(scene_id)
    spelled = procedural_scene_id(
        seed, procedural_floors(scene_id) or 1, procedural_preset(scene_id)
    )
    if scene_id != spelled:
        raise ConfigError(f"scene {scene_id!r} is spelled {spelled!r}; each house has one id")
    return seed


class SceneCache:
    """Simulators by scene id, least recently used dropped first. ``houses`` gives the house
    of a scene id (by default :func:`scene_house`, built or read anew): caches used side by
    side share one that keeps what it built, since a house is never changed by its
    simulator."""

    def __init__(
        self,
        config: SimulatorConfig | None = None,
        capacity: int = 2,
        scenes_dir: str | Path | None = None,
        houses: Callable[[str, Path | None], House] | None = None,
    ) -> None:
        self.config = config
        self.capacity = capacity
        self.scenes_dir = None if scenes_dir is None else Path(scenes_dir)
        self.houses = houses or scene_house
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
        return self.houses(scene_id, self.scenes_dir)

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
