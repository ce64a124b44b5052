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
