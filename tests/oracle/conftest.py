"""One generated house shared by the oracle tests of a module."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from vlln.sim.simulator import Simulator
from vlln.tasks.scenes import SceneCache, procedural_scene_id

HOUSE_SEED = 2


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    cache = SceneCache()
    yield cache
    cache.close()


@pytest.fixture(scope="module")
def sim(scenes: SceneCache) -> Simulator:
    return scenes.get(procedural_scene_id(HOUSE_SEED))
