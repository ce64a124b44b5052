from __future__ import annotations

from collections.abc import Iterator

import pytest

from vlln.tasks.scenes import SceneCache


@pytest.fixture(scope="module")
def scenes() -> Iterator[SceneCache]:
    """Simulators shared by one module's runs (a module's own, as a GL context that another
    part of the process creates and closes later would leave this one's not current)."""
    cache = SceneCache()
    yield cache
    cache.close()
