"""Named house distributions: which houses a seed gives under each preset.

``small`` is the generator's default house (one storey, about six rooms): fast to build and
to play, it drives ``make demo`` and the fast tests. ``mp3d`` is calibrated to the
Matterport3D buildings that VL-LN Bench uses (docs/world-statistics.md gives each target
statistic with its source): three storeys in most houses, one or two in some, about 26
regions, some 400 m² to walk on and around 240 annotated instances, nine in ten of them
sharing their category with others in the house. Within ``mp3d`` the number of storeys and
the room counts are drawn per seed, from the seed alone, so a house is the same wherever and
whenever it is built.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from vlln.errors import ConfigError
from vlln.world.generator.house import generate_house
from vlln.world.generator.params import HouseParameters
from vlln.world.model import House


@dataclass(frozen=True)
class HousePreset:
    """A distribution over house parameters, drawn per seed."""

    name: str
    summary: str
    base: HouseParameters
    floor_weights: tuple[float, ...] = (1.0,)  # P(1 storey), P(2), P(3)
    rooms_per_storey: tuple[int, int] | None = None  # inclusive range drawn per seed
    area_per_room: tuple[float, float] = field(default=(0.0, 0.0))  # m² range per room

    def parameters(self, seed: int, floors: int | None = None) -> HouseParameters:
        """The parameters of house ``seed``; ``floors`` forces the number of storeys."""
        if self.rooms_per_storey is None:
            params = self.base if floors is None else replace(self.base, floors=floors)
            params.validate()
            return params
        rng = np.random.default_rng(np.random.SeedSequence([int(seed), _PRESET_STREAM]))
        weights = np.asarray(self.floor_weights, dtype=float)
        drawn = 1 + int(rng.choice(len(weights), p=weights / weights.sum()))
        low, high = self.rooms_per_storey
        rooms = int(rng.integers(low, high + 1))
        area_low, area_high = self.area_per_room
        params = replace(
            self.base,
            floors=drawn if floors is None else floors,
            min_rooms=rooms,
            max_rooms=rooms,
            min_area=rooms * area_low,
            max_area=rooms * area_high,
        )
        params.validate()
        return params


# The stream of a seed's parameter draw, apart from the plan/shell/furniture streams.
_PRESET_STREAM = 0x5EED

SMALL = HousePreset(
    name="small",
    summary="one storey, about 6 rooms and 125 objects (demo, fast tests)",
    base=HouseParameters(),
)
MP3D = HousePreset(
    name="mp3d",
    summary="calibrated to Matterport3D as VL-LN uses it (docs/world-statistics.md)",
    base=HouseParameters(clutter=0.5, category_variety=0.62, repeats=2.0),
    floor_weights=(0.1, 0.2, 0.7),
    rooms_per_storey=(8, 13),
    area_per_room=(20.0, 28.0),
)
PRESETS: dict[str, HousePreset] = {preset.name: preset for preset in (SMALL, MP3D)}
DEFAULT_PRESET = MP3D.name
"""The benchmark's houses: splits, evaluation and episode files use this preset unless told."""


def preset(name: str) -> HousePreset:
    """The preset called ``name``; an unknown name is refused with the valid ones."""
    try:
        return PRESETS[name]
    except KeyError:
        raise ConfigError(
            f"unknown house preset {name!r}; choose one of: {', '.join(PRESETS)}"
        ) from None


def house_name(preset_name: str, seed: int, floors: int = 1) -> str:
    """``house_<seed>`` (``_2f``/``_3f`` with storeys) for ``small``, ``mp3d_<seed>`` for
    ``mp3d``, whose storeys follow from the seed."""
    if preset_name == SMALL.name:
        return f"house_{seed:05d}" + (f"_{floors}f" if floors > 1 else "")
    preset(preset_name)
    return f"{preset_name}_{seed:05d}"


def generate_preset_house(seed: int, preset_name: str, floors: int | None = None) -> House:
    """House ``seed`` of a preset, named as its scene id names it."""
    chosen = preset(preset_name)
    params = chosen.parameters(seed, floors)
    house = generate_house(seed, params)
    return replace(house, name=house_name(preset_name, seed, params.floors))
