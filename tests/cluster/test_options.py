"""The shared Ray settings: ``--ray local`` leaves the choice of cluster to Ray, an empty
address is refused in one line, and retries and chunks are bounded."""

from __future__ import annotations

import pytest

from vlln.cluster.options import RayChunkOptions, RayOptions
from vlln.errors import ConfigError


def test_ray_spellings_give_the_address_ray_init_receives() -> None:
    assert RayOptions.build({}).ray is None
    assert RayOptions.build({"ray": "local"}).ray_address is None
    assert RayOptions.build({"ray": "auto"}).ray_address == "auto"
    assert RayOptions.build({"ray": "10.0.0.2:6379"}).ray_address == "10.0.0.2:6379"


def test_bad_ray_settings_are_one_line_naming_the_flag() -> None:
    with pytest.raises(ConfigError, match=r"^--ray: give an address \(host:port\), auto"):
        RayOptions.build({"ray": " "})
    with pytest.raises(ConfigError, match=r"^--retries: Input should be greater than or equal"):
        RayOptions.build({"retries": -1})
    with pytest.raises(ConfigError, match=r"^--chunk: Input should be greater than or equal"):
        RayChunkOptions.build({"chunk": 0})
