"""Optional installs (pip extras), checked before a command uses one: a missing package is one
line naming the install, not a ``ModuleNotFoundError`` from deep inside an import."""

from __future__ import annotations

from collections.abc import Sequence
from importlib import import_module
from pathlib import Path

from vlln.errors import ConfigError

# The packages a command of each extra imports (pyproject.toml lists what pip installs).
SERVE_PACKAGES = ("fastapi", "uvicorn")
SERVICE_BENCH_PACKAGES = (*SERVE_PACKAGES, "aiohttp")


def install_command(extra: str) -> str:
    """The pip line that adds ``extra`` to this install. vlln is not on a package index, so
    ``pip install 'vlln[extra]'`` fails: from a clone (an editable install) it is the clone's
    path, otherwise the wheel's or clone's that vlln was installed from."""
    root = Path(__file__).resolve().parents[2]
    if (root / "pyproject.toml").is_file():
        return f"pip install -e '{root}[{extra}]'"
    return f"pip install '<the vlln clone or wheel you installed>[{extra}]'"


def require_extra(extra: str, what: str, packages: Sequence[str]) -> None:
    """Raise one line naming :func:`install_command` when one of ``packages`` cannot be
    imported (checked in order, stopping at the first, so a later package is never imported
    without the one it builds on)."""
    for name in packages:
        try:
            import_module(name)
        except ImportError as error:
            raise ConfigError(
                f"{what} needs {name}, which is not installed; "
                f"install the {extra} extra with: {install_command(extra)}"
            ) from error
