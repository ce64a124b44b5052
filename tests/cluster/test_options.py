"""The shared Ray settings: ``--ray`` alone leaves the choice of cluster to Ray, and retries
and chunks are bounded."""

from __future__ import annotations

import argparse

import pytest

from vlln.cli.generated import add_config_command
from vlln.cluster.options import RayChunkOptions, RayOptions
from vlln.errors import ConfigError


def test_ray_spellings_give_the_address_ray_init_receives() -> None:
    parser = argparse.ArgumentParser()
    built: list[RayOptions] = []

    def keep(config: RayOptions) -> int:
        built.append(config)
        return 0

    add_config_command(parser.add_subparsers(), "run", RayOptions, keep, help="")
    for given, address in (([], None), (["--ray"], None), (["--ray", "auto"], "auto")):
        args = parser.parse_args(["run", *given, "--retries", "0"])
        assert args.handler(args) == 0
        assert built[-1].ray_address == address and built[-1].retries == 0
    assert built[0].ray is None and built[1].ray == ""


def test_bad_ray_settings_are_one_line_naming_the_flag() -> None:
    with pytest.raises(ConfigError, match=r"^--retries: Input should be greater than or equal"):
        RayOptions.build({"retries": -1})
    with pytest.raises(ConfigError, match=r"^--chunk: Input should be greater than or equal"):
        RayChunkOptions.build({"chunk": 0})
