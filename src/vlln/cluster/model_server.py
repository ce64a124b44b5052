"""One copy of a model agent's model per node, shared by the node's workers (``vlln eval --ray``).

Without it every worker process would load its own copy of the ``vlln`` agent's model (GBs of
weights, each on the GPU). Instead the driver starts one named actor per node of the cluster
(the node id in its name, pinned there by node affinity) before any chunk is sent, and waits
until each has loaded the model: the actors hold their CPUs and GPUs from then on, so the
chunks can never take the resources a server still waits for. A chunk's agents send every
generate request to their node's server (a node without one, lacking the resources, uses
another node's). The server answers the requests that arrive while it is busy in one padded
batch: greedy decoding with left padding gives each the reply it gets alone, so the records
equal a local run's.

A killed server is restarted by Ray, loads the model again, and the calls it had in hand are
sent again (``max_restarts`` and ``max_task_retries`` set to the run's retries). A server lost
for good (its restarts spent, or its node gone) fails the chunk that was using it
(:class:`ModelServerLost`), which is then re-run like the chunk of a dead worker; no episode
is recorded from a half-answered model.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from vlln.agents.local.backend import TransformersBackend
from vlln.agents.local.batching import BatchingModel
from vlln.agents.local.options import VllnOptions
from vlln.agents.model.backend import ModelReply
from vlln.cluster.options import ServingOptions
from vlln.cluster.scheduler import ClusterError, import_ray
from vlln.errors import ConfigError, VllnError
from vlln.eval.config import EvalConfig
from vlln.prompt import Conversation


class ModelServerLost(VllnError):
    """A chunk's model server died for good while the chunk was playing."""


@dataclass(frozen=True)
class ServerStats:
    """What one node's server did in a run."""

    node_id: str
    backend: str
    requests: int
    batches: int
    largest_batch: int
    restarted: bool  # this copy was loaded after Ray restarted a killed server

    def describe(self) -> str:
        again = ", restarted after a failure" if self.restarted else ""
        return (
            f"{self.backend} on node {self.node_id[:12]}: {self.requests} requests in "
            f"{self.batches} batches (up to {self.largest_batch} at once){again}"
        )


def served_model(config: EvalConfig) -> VllnOptions | None:
    """The local model ``config``'s agent runs, to be served, or None for an agent without
    one (the config checked its options against :class:`VllnOptions`)."""
    if config.agent != "vlln":
        return None
    assert isinstance(config.agent_options, VllnOptions)
    return config.agent_options


class ModelServer:
    """The Ray actor holding one node's copy of the model (module doc)."""

    def __init__(self, settings: VllnOptions, max_batch: int) -> None:
        context = import_ray().get_runtime_context()
        self.node_id = context.get_node_id()
        self.restarted = bool(context.was_current_actor_reconstructed)
        self.error: str | None = None
        self.model: BatchingModel | None = None
        try:
            backend = TransformersBackend(settings.model_dir, settings.device, settings.max_tokens)
            self.model = BatchingModel(backend, max_batch)
        except Exception as error:  # reported by ready(), as one line on the driver
            self.error = f"the model server on node {self.node_id[:12]} could not load the model: "
            self.error += _one_line(error)

    async def ready(self) -> str | None:
        """None once the model is loaded, else why it could not be."""
        return self.error

    async def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        if self.model is None:  # a restart whose load failed: no reply is ever coming
            raise ModelServerLost(self.error or "no model")
        return await self.model.generate(conversation, images)

    async def stats(self) -> ServerStats:
        model = self.model
        if model is None:
            return ServerStats(self.node_id, "no model", 0, 0, 0, self.restarted)
        return ServerStats(
            self.node_id,
            model.backend.backend,
            model.requests,
            model.batches,
            model.largest_batch,
            self.restarted,
        )


def _one_line(error: Exception) -> str:
    """Our own errors as they are; anything else (a broken checkpoint) with its type."""
    text = str(error) if isinstance(error, VllnError) else f"{type(error).__name__}: {error}"
    return text.strip().splitlines()[0][:300]


class ServedModel:
    """A :class:`~vlln.agents.model.backend.VisionLanguageModel` whose calls go to a server.

    A server lost for good gives a failed reply (the agent cannot tell), and ``lost`` says
    why, so the chunk is failed and re-run instead of recorded.
    """

    def __init__(self, server: Any) -> None:
        self.server = server
        self.lost: str | None = None

    @property
    def backend(self) -> str:
        return "ray-model-server"

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        ray = import_ray()
        started = time.perf_counter()
        try:
            reply: ModelReply = ray.get(self.server.generate.remote(conversation, list(images)))
        except ray.exceptions.RayActorError as error:
            self.lost = f"the model server died: {type(error).__name__}"
            return ModelReply(text=None, error=self.lost)
        except ModelServerLost as error:  # raised in the server, wrapped by Ray
            cause = getattr(error, "cause", error)
            self.lost = str(cause).strip()[:300]
            return ModelReply(text=None, error=self.lost)
        waited_ms = (time.perf_counter() - started) * 1000.0
        return ModelReply(
            reply.text, reply.error, waited_ms, reply.prompt_tokens, reply.completion_tokens
        )


def server_for_this_node(servers: Mapping[str, Any]) -> Any:
    """This node's server, or (a node without one) another node's, spread by process."""
    node = import_ray().get_runtime_context().get_node_id()
    if node in servers:
        return servers[node]
    nodes = sorted(servers)
    return servers[nodes[os.getpid() % len(nodes)]]


def start_model_servers(
    settings: VllnOptions, options: ServingOptions, max_retries: int
) -> dict[str, Any]:
    """One loaded server per node that has the resources, as {node id: actor handle}."""
    ray = import_ray()
    from ray.util.scheduling_strategies import NodeAffinitySchedulingStrategy

    gpus = options.model_gpus
    if gpus is None:
        on_cpu = (settings.device or "").startswith("cpu")
        gpus = 1.0 if ray.cluster_resources().get("GPU", 0) > 0 and not on_cpu else 0.0
    nodes = [
        node["NodeID"]
        for node in ray.nodes()
        if node["Alive"]
        and node["Resources"].get("CPU", 0) >= options.model_cpus
        and node["Resources"].get("GPU", 0) >= gpus
    ]
    if not nodes:
        raise ConfigError(
            f"no node of the cluster has {options.model_cpus:g} CPUs and {gpus:g} GPUs for the "
            "model server; lower --model-cpus / --model-gpus or add a node that has them"
        )
    digest = hashlib.sha1(repr(settings).encode()).hexdigest()[:8]
    actor = ray.remote(ModelServer)
    servers = {
        node: actor.options(
            name=f"vlln-model-{digest}-{node}",
            get_if_exists=True,
            num_cpus=options.model_cpus,
            num_gpus=gpus,
            max_restarts=max_retries,
            max_task_retries=max_retries,
            scheduling_strategy=NodeAffinitySchedulingStrategy(node, soft=False),
        ).remote(settings, options.model_batch)
        for node in nodes
    }
    try:
        errors = ray.get([server.ready.remote() for server in servers.values()])
    except ray.exceptions.RayActorError as error:
        stop_model_servers(servers)
        raise ClusterError(
            f"a model server died while loading the model (out of memory?): {type(error).__name__}"
        ) from None
    failed = next((error for error in errors if error is not None), None)
    if failed is not None:
        stop_model_servers(servers)
        raise ConfigError(failed)
    return servers


def stop_model_servers(servers: Mapping[str, Any]) -> list[ServerStats]:
    """Stop the servers; what each still alive did."""
    ray = import_ray()
    stats: list[ServerStats] = []
    for server in servers.values():
        with contextlib.suppress(ray.exceptions.RayActorError):  # lost for good: no stats
            stats.append(ray.get(server.stats.remote()))
        ray.kill(server, no_restart=True)
    return stats
