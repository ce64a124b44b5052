"""What every command module shares: the type of the object it adds its commands to."""

from __future__ import annotations

import argparse
from typing import TypeAlias

Commands: TypeAlias = "argparse._SubParsersAction[argparse.ArgumentParser]"
"""The object ``add_subparsers`` returns, to which each module adds its commands."""
