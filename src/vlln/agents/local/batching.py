"""Requests from many callers answered in batches: what one model shared by a node's workers
needs (:mod:`vlln.cluster.model_server`), and episodes played side by side in one process
(:class:`ThreadedBatching`, for ``vlln eval --concurrent``).

Requests that arrive while the model is busy wait, and the next forward pass answers up to
``max_batch`` of them together; no request ever waits for company, so a lone caller is
answered as fast as without batching. Greedy decoding with left padding gives every request
the reply it gets alone (tested with the tiny model).
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Coroutine, Sequence
from typing import Any, TypeVar

from vlln.agents.local.backend import TransformersBackend
from vlln.agents.model.backend import ModelReply
from vlln.errors import ConfigError
from vlln.prompt import Conversation

DEFAULT_MAX_BATCH = 8
T = TypeVar("T")

_Waiting = tuple[Conversation, Sequence[bytes], "asyncio.Future[ModelReply]"]


class BatchingModel:
    """``backend`` behind an asyncio queue; the model runs in a thread, so requests keep
    arriving while it works. Counts what it did, for the run's report.

    With ``callers`` set (the callers in play, kept up to date by :meth:`join` and
    :meth:`leave`), a batch starts only once each caller in play waits (or ``max_batch`` do):
    callers that take turns between their calls (:mod:`vlln.eval.side_by_side`) would
    otherwise fall into alternating batches of one and of the rest."""

    def __init__(
        self,
        backend: TransformersBackend,
        max_batch: int = DEFAULT_MAX_BATCH,
        callers: int | None = None,
    ) -> None:
        if max_batch < 1:
            raise ConfigError(f"--model-batch must be at least 1, got {max_batch}")
        self.backend = backend
        self.max_batch = max_batch
        self.callers = callers
        self.requests = self.batches = self.largest_batch = 0
        self._waiting: list[_Waiting] = []
        self._drainer: asyncio.Task[None] | None = None  # answering the waiting calls

    def describe(self) -> str:
        """What it did, e.g. ``52 calls in 20 batches (up to 4 at once)``."""
        return (
            f"{self.requests} calls in {self.batches} batches (up to {self.largest_batch} at once)"
        )

    async def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        """The reply to one call, computed in a batch with the calls waiting beside it."""
        future: asyncio.Future[ModelReply] = asyncio.get_running_loop().create_future()
        self._waiting.append((conversation, images, future))
        self.requests += 1
        self._start()
        return await future

    async def join(self) -> None:
        """One more caller in play (``callers`` set)."""
        self.callers = (self.callers or 0) + 1

    async def leave(self) -> None:
        """A caller has made its last call; the others need not wait for it."""
        self.callers = max(0, (self.callers or 0) - 1)
        self._start()

    def _ready(self) -> bool:
        """Whether the waiting calls make a batch (class doc)."""
        if not self._waiting:
            return False
        return self.callers is None or len(self._waiting) >= min(self.max_batch, self.callers)

    def _start(self) -> None:
        if (self._drainer is None or self._drainer.done()) and self._ready():
            self._drainer = asyncio.get_running_loop().create_task(self._drain())

    async def _drain(self) -> None:
        """Answer waiting calls, up to ``max_batch`` at a time, while they make a batch."""
        while self._ready():
            batch = self._waiting[: self.max_batch]
            del self._waiting[: self.max_batch]
            self.batches += 1
            self.largest_batch = max(self.largest_batch, len(batch))
            calls = [(conversation, images) for conversation, images, _ in batch]
            try:
                replies = await asyncio.to_thread(self.backend.generate_many, calls)
            except Exception as error:  # not a failed call (those are replies): a bug
                for _, _, future in batch:
                    future.set_exception(error)
                continue
            for (_, _, future), reply in zip(batch, replies, strict=True):
                future.set_result(reply)


class ThreadedBatching:
    """A :class:`BatchingModel` for callers on threads: its event loop runs in a thread of its
    own, and :meth:`generate` blocks the calling thread until its reply is in, so each caller
    sees a plain :class:`~vlln.agents.model.backend.VisionLanguageModel`. Callers that take
    turns say when they are in play (:meth:`join`, :meth:`leave`), and a batch waits for each
    of them. :meth:`close` stops the loop."""

    def __init__(self, backend: TransformersBackend, max_batch: int = DEFAULT_MAX_BATCH) -> None:
        self.model = BatchingModel(backend, max_batch, callers=0)
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(
            target=self._loop.run_forever, name="vlln-model-batching", daemon=True
        )
        self._thread.start()

    @property
    def backend(self) -> str:
        return self.model.backend.backend

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        """The reply to one call, answered in a batch with the calls of the other threads."""
        return self._run(self.model.generate(conversation, images))

    def join(self) -> None:
        """One more caller in play: batches wait for its calls until it leaves."""
        self._run(self.model.join())

    def leave(self) -> None:
        """A caller has made its last call."""
        self._run(self.model.leave())

    def _run(self, call: Coroutine[Any, Any, T]) -> T:
        return asyncio.run_coroutine_threadsafe(call, self._loop).result()

    def close(self) -> None:
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join()
        self._loop.close()

    def __enter__(self) -> ThreadedBatching:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()
