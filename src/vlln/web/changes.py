"""A version number that pages can wait on (long polling), bumped from any thread."""

from __future__ import annotations

import asyncio
import contextlib
import threading


class ChangeSignal:
    """Counts changes; :meth:`wait_beyond` returns once the count passes a version.

    Sessions change on their own threads while requests wait on the event loop, so a bump
    schedules the wake-up on the loop (``call_soon_threadsafe``); without a loop (in-process
    use) only the count moves.
    """

    def __init__(self, loop: asyncio.AbstractEventLoop | None = None) -> None:
        self._loop = loop
        self._lock = threading.Lock()
        self._version = 1
        self._event: asyncio.Event | None = None

    def attach(self, loop: asyncio.AbstractEventLoop) -> None:
        """Wake waiters on ``loop`` from now on (the server's loop, once it runs)."""
        self._loop = loop

    @property
    def version(self) -> int:
        return self._version

    def bump(self) -> None:
        with self._lock:
            self._version += 1
        if self._loop is not None and not self._loop.is_closed():
            with contextlib.suppress(RuntimeError):  # the loop closed meanwhile
                self._loop.call_soon_threadsafe(self._wake)

    def _wake(self) -> None:
        event, self._event = self._event, None
        if event is not None:
            event.set()

    async def wait_beyond(self, version: int, timeout_s: float) -> None:
        """Return when the version is above ``version``, or after ``timeout_s``."""
        if self._version > version:
            return
        if self._event is None:
            self._event = asyncio.Event()
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(self._event.wait(), timeout_s)
