"""The settings every command that can run on Ray shares (``--ray``, ``--retries``,
``--chunk``), as config classes a command's config inherits (docs/ray.md)."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field, field_validator

from vlln.cluster.scheduler import DEFAULT_MAX_RETRIES
from vlln.config import Config

LOCAL_CLUSTER = "local"
"""``--ray local``: ``RAY_ADDRESS``'s cluster when that is set, else a fresh one on this
machine for the run (Ray's own choice when it is given no address)."""


class RayOptions(Config):
    """Where to run on Ray, and how often to re-run a task whose worker died."""

    ray: str | None = None
    """run on a Ray cluster: ADDRESS (host:port), auto (the one on this machine) or local
    (RAY_ADDRESS's, else a fresh one for the run); none: without Ray"""
    retries: Annotated[int, Field(ge=0)] = DEFAULT_MAX_RETRIES
    """re-runs of a task whose worker died"""

    @field_validator("ray")
    @classmethod
    def _ray_address(cls, value: str | None) -> str | None:
        if value is not None and not value.strip():
            raise ValueError(
                "give an address (host:port), auto (a cluster started on this machine) or "
                "local (a fresh one for the run)"
            )
        return value

    @property
    def ray_address(self) -> str | None:
        """The address to hand to ``ray.init`` (none for ``local``: Ray's own choice)."""
        return None if self.ray == LOCAL_CLUSTER else self.ray


class RayChunkOptions(RayOptions):
    """:class:`RayOptions` for episode work, sent in chunks of whole episodes."""

    chunk: Annotated[int, Field(ge=1)] = 4
    """episodes per Ray task"""
