"""The settings every command that can run on Ray shares (``--ray``, ``--retries``,
``--chunk``) and those of the vlln agent's model server on each node (``--model-cpus``,
``--model-gpus``, ``--model-batch``), as config classes a command's config inherits
(docs/ray.md)."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from vlln.agents.local.batching import DEFAULT_MAX_BATCH
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


class ServingOptions(Config):
    """What each node's model server asks of its node, and how many requests it batches."""

    model_cpus: Annotated[float, Field(ge=0)] = 1.0
    """--ray: CPUs of the vlln agent's model server on each node"""
    model_gpus: Annotated[float | None, Field(ge=0)] = None
    """--ray: its GPUs (none: 1 when the cluster has GPUs and --device is not cpu, else 0)"""
    model_batch: Annotated[int, Field(ge=1)] = DEFAULT_MAX_BATCH
    """--ray: most requests the model server answers at once"""
