"""The settings every command that can run on Ray shares (``--ray``, ``--retries``,
``--chunk``), as config classes a command's config inherits (docs/ray.md)."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES
from vlln.config import BareFlag, Config


class RayOptions(Config):
    """Where to run on Ray, and how often to re-run a task whose worker died."""

    ray: Annotated[str | None, BareFlag("")] = None
    """run on a Ray cluster: ADDRESS, 'auto', or the flag alone for RAY_ADDRESS or a local
    one (docs/ray.md)"""
    retries: Annotated[int, Field(ge=0)] = DEFAULT_MAX_RETRIES
    """--ray: re-runs of a task whose worker died"""

    @property
    def ray_address(self) -> str | None:
        """The address to hand to ``ray.init`` (none for the flag alone: Ray's own choice)."""
        return self.ray or None


class RayChunkOptions(RayOptions):
    """:class:`RayOptions` for episode work, sent in chunks of whole episodes."""

    chunk: Annotated[int, Field(ge=1)] = 4
    """--ray: episodes per Ray task"""
