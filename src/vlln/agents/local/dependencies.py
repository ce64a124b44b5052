"""The optional install the local model needs, checked before anything uses it."""

from __future__ import annotations

from collections.abc import Sequence
from importlib import import_module

from vlln.errors import ConfigError

MODEL_PACKAGES = ("torch", "transformers", "accelerate")
INSTALL_HINT = "pip install 'vlln[model]'"


def require_model_extra(packages: Sequence[str] = MODEL_PACKAGES) -> None:
    """Raise one line naming the install when a package of the ``model`` extra is missing
    (checked in order and stopping at the first, so transformers is never imported without
    torch, which would only print warnings)."""
    for name in packages:
        try:
            import_module(name)
        except ImportError as error:
            raise ConfigError(
                f"the local model needs {name}, which is not installed; "
                f"install the model extra with: {INSTALL_HINT}"
            ) from error
