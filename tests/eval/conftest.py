from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from vlln.tasks.scenes import SceneCache
from vlln.tasks.split_files import load_or_build_split


@pytest.fixture(scope="session")
def split_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The test split's first house, built once for every evaluation test."""
    cache = tmp_path_factory.mktemp("episodes")
    load_or_build_split("test", "iign", 1, cache, progress=False)
    return cache


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    """Simulators shared by one module's runs (a module's own, as a GL context that another
    part of the process creates and closes later would leave this one's not current)."""
    cache = SceneCache()
    yield cache
    cache.close()
