"""The optional install the local model needs, checked before anything uses it."""

from __future__ import annotations

from collections.abc import Sequence

from vlln.extras import require_extra

MODEL_PACKAGES = ("torch", "transformers", "accelerate")


def require_model_extra(packages: Sequence[str] = MODEL_PACKAGES) -> None:
    """Raise one line naming the install when a package of the ``model`` extra is missing
    (checked in order and stopping at the first, so transformers is never imported without
    torch, which would only print warnings)."""
    require_extra("model", "the local model", packages)
