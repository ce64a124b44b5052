"""Options that several commands share."""

from __future__ import annotations

import argparse
from typing import TypeAlias

Commands: TypeAlias = "argparse._SubParsersAction[argparse.ArgumentParser]"
"""The object ``add_subparsers`` returns, to which each module adds its commands."""


def add_ray_options(parser: argparse.ArgumentParser, chunks: bool) -> None:
    """``--ray [ADDRESS]``, ``--retries`` and, for episodes, ``--chunk`` (docs/ray.md)."""
    parser.add_argument(
        "--ray",
        nargs="?",
        const="",
        metavar="ADDRESS",
        help="run on a Ray cluster (ADDRESS, 'auto', or none for RAY_ADDRESS or a local one)",
    )
    if chunks:
        parser.add_argument(
            "--chunk", type=int, default=4, help="episodes per Ray task (default 4)"
        )
    parser.add_argument(
        "--retries", type=int, default=3, help="re-runs of a task whose worker died (default 3)"
    )


def add_preset_option(parser: argparse.ArgumentParser, benchmark_default: bool = True) -> None:
    """``--preset``: which houses (:mod:`vlln.world.generator.presets`); the benchmark's
    (``DEFAULT_PRESET``) unless ``benchmark_default`` is false, ``small`` for the demo and fast
    tests."""
    from vlln.world.generator.presets import DEFAULT_PRESET, PRESETS

    default = DEFAULT_PRESET if benchmark_default else None
    shown = "none: the generator's parameters" if default is None else default
    parser.add_argument(
        "--preset",
        default=default,
        choices=sorted(PRESETS),
        help=f"houses: mp3d (the benchmark's, calibrated to Matterport3D) or small (demo, fast "
        f"tests); default {shown}",
    )
