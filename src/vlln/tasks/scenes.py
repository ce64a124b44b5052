"""Scene ids and the simulators behind them.

Procedural houses are named ``vlln/house_<seed>`` in episode files (the released data uses a
path to a scan there); :class:`SceneCache` builds a simulator per scene and keeps the most
recent few, since runners visit episodes scene by scene.
"""

from __future__ import annotations

import re
from collections import OrderedDict

from vlln.errors import ConfigError
from vlln.sim.simulator import Simulator, SimulatorConfig
from vlln.world.generator import generate_house

_PROCEDURAL = re.compile(r"^vlln/house_(\d+)$")


def procedural_scene_id(seed: int) -> str:
    return f"vlln/house_{seed:05d}"


def procedural_seed(scene_id: str) -> int:
    match = _PROCEDURAL.match(scene_id)
    if match is None:
        raise ConfigError(
            f"scene {scene_id!r} is not a built-in procedural house (vlln/house_<seed>); "
            "importers for other scenes are separate"
        )
    return int(match.group(1))


class SceneCache:
    """Simulators by scene id, least recently used dropped first."""

    def __init__(self, config: SimulatorConfig | None = None, capacity: int = 2) -> None:
        self.config = config
        self.capacity = capacity
        self._sims: OrderedDict[str, Simulator] = OrderedDict()

    def get(self, scene_id: str) -> Simulator:
        sim = self._sims.get(scene_id)
        if sim is not None:
            self._sims.move_to_end(scene_id)
            return sim
        sim = Simulator(generate_house(procedural_seed(scene_id)), self.config)
        self._sims[scene_id] = sim
        while len(self._sims) > self.capacity:
            _, old = self._sims.popitem(last=False)
            old.close()
        return sim

    def close(self) -> None:
        for sim in self._sims.values():
            sim.close()
        self._sims.clear()
