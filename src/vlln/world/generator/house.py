"""Seeded procedural houses: floor plan, shell, furniture, words and one static mesh.

The seed is split into independent streams for the plan, the shell and the furniture, so a
different catalogue changes what stands in the rooms but not the rooms themselves. The same
seed and parameters give byte-identical records and meshes.

A house takes one to two seconds to generate, and processes often make one again: a second
evaluation, data build or simulator in the same process, every test of a module. So the last
:data:`RECENT_HOUSES` of the built-in catalogue are kept, pickled (a few MB each), and a copy
is handed out in tens of milliseconds: callers may change what they get.
"""

from __future__ import annotations

import pickle
from functools import lru_cache

import numpy as np

from vlln.errors import HouseParametersError
from vlln.world.catalogue.registry import Catalogue, default_catalogue
from vlln.world.generator.contents import EXPECTED_MEAN
from vlln.world.generator.furnishing import furnish
from vlln.world.generator.layout import plan_floor
from vlln.world.generator.params import HouseParameters
from vlln.world.generator.storeys import build_storeys
from vlln.world.generator.structure import build_structure
from vlln.world.mesh import Mesh
from vlln.world.model import House, HouseGeometry
from vlln.world.relations import build_relations


def house_vocabulary(catalogue: Catalogue, variety: float, rng: np.random.Generator) -> Catalogue:
    """The catalogue one house furnishes from: every category that some room type nearly
    always has (beds, toilets, stoves), and a ``variety`` share of the others, so a house
    repeats fewer kinds of object more often, as a real building does."""
    kept = [
        category
        for category in catalogue
        if max(category.rooms.values(), default=0.0) >= EXPECTED_MEAN or rng.random() < variety
    ]
    return Catalogue(kept)


def generate_house(
    seed: int, params: HouseParameters | None = None, catalogue: Catalogue | None = None
) -> House:
    """The house ``house_{seed:05d}``: rooms, doors, instances, relations and geometry."""
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
        raise HouseParametersError(f"seed={seed!r} must be a whole number >= 0")
    params = params if params is not None else HouseParameters()
    params.validate()
    if catalogue is not None:
        return _generated(int(seed), params, catalogue)
    house: House = pickle.loads(_recent(int(seed), params, default_catalogue().fingerprint()))
    return house


RECENT_HOUSES = 6


@lru_cache(maxsize=RECENT_HOUSES)
def _recent(seed: int, params: HouseParameters, fingerprint: str) -> bytes:
    """A house of the built-in catalogue, pickled; ``fingerprint`` (the catalogue's) keys it."""
    house = _generated(seed, params, default_catalogue())
    return pickle.dumps(house, protocol=pickle.HIGHEST_PROTOCOL)


def _generated(seed: int, params: HouseParameters, catalogue: Catalogue) -> House:
    """The house, built from nothing."""
    # A fourth stream draws the house's categories, leaving the first three as they were.
    plan_rng, shell_rng, furniture_rng, vocabulary_rng = (
        np.random.default_rng(child) for child in np.random.SeedSequence(int(seed)).spawn(4)
    )
    if params.category_variety < 1.0:
        catalogue = house_vocabulary(catalogue, params.category_variety, vocabulary_rng)
    if params.floors > 1:
        rooms, doors, instances, mesh = build_storeys(
            params, catalogue, plan_rng, shell_rng, furniture_rng
        )
    else:
        plan = plan_floor(params, plan_rng)
        shell = build_structure(plan, params, shell_rng)
        objects = furnish(plan, params, catalogue, furniture_rng)
        rooms, doors = plan.rooms, plan.doors
        instances = [obj.instance for obj in objects]
        mesh = Mesh.concatenate([shell, *(obj.mesh for obj in objects)])
    return House(
        name=f"house_{int(seed):05d}" + (f"_{params.floors}f" if params.floors > 1 else ""),
        rooms=rooms,
        doors=doors,
        instances=instances,
        relations=build_relations(instances),
        geometry=HouseGeometry(mesh),
        seed=int(seed),
    )
