"""Optional installs (pip extras), checked before a command uses one: a missing package is one
line naming the install, not a ``ModuleNotFoundError`` from deep inside an import."""

from __future__ import annotations

from collections.abc import Sequence
from importlib import import_module

from vlln.errors import ConfigError

# The packages a command of each extra imports (pyproject.toml lists what pip installs).
SERVE_PACKAGES = ("fastapi", "uvicorn")
SERVICE_BENCH_PACKAGES = (*SERVE_PACKAGES, "aiohttp")


def require_extra(extra: str, what: str, packages: Sequence[str]) -> None:
    """Raise one line naming ``pip install 'vlln[extra]'`` when one of ``packages`` cannot be
    imported (checked in order, stopping at the first, so a later package is never imported
    without the one it builds on)."""
    for name in packages:
        try:
            import_module(name)
        except ImportError as error:
            raise ConfigError(
                f"{what} needs {name}, which is not installed; "
                f"install the {extra} extra with: pip install 'vlln[{extra}]'"
            ) from error
