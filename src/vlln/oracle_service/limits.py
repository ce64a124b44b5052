"""How many houses the service may build per minute, per client and in total.

Building a house (generation and a simulator) takes about half a second of CPU and tens of
megabytes; a client that names a new scene in every request could keep the server building
and starve every other client. A sliding one-minute window bounds the builds each client
(by address) may cause and the builds of all clients together; a request over either bound
gets 429 with the seconds to wait.
"""

from __future__ import annotations

import math
import time
from collections import deque
from collections.abc import Callable

from vlln.oracle_service.sessions import ServiceError

WINDOW_S = 60.0


class BuildLimiter:
    """Admits a house build if neither the client's nor the total window is full."""

    def __init__(
        self, per_client: int, total: int, clock: Callable[[], float] = time.monotonic
    ) -> None:
        self.per_client = per_client
        self.total = total
        self._clock = clock
        self._all: deque[float] = deque()
        self._clients: dict[str, deque[float]] = {}

    def admit(self, client: str) -> None:
        """Count one build for ``client``, or raise a 429 :class:`ServiceError`."""
        now = self._clock()
        self._forget_before(now - WINDOW_S)
        mine = self._clients.get(client, deque())
        for window, limit, whose in (
            (mine, self.per_client, "this client's"),
            (self._all, self.total, "the server's"),
        ):
            if len(window) >= limit:
                wait = math.ceil(window[0] + WINDOW_S - now)
                raise ServiceError(
                    429,
                    "too many house builds",
                    f"{whose} limit of {limit} house builds per minute is reached; retry in "
                    f"{max(1, wait)} s, or keep to scenes already built",
                )
        mine.append(now)
        self._clients[client] = mine
        self._all.append(now)

    def _forget_before(self, cutoff: float) -> None:
        while self._all and self._all[0] < cutoff:
            self._all.popleft()
        for client in list(self._clients):
            window = self._clients[client]
            while window and window[0] < cutoff:
                window.popleft()
            if not window:
                del self._clients[client]
