"""Request rates and response headers that every page and API call gets."""

from __future__ import annotations

import time
from collections.abc import Callable

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from vlln.http.responses import error_response

# Pages load their scripts and styles from this server only, never inline: a question or
# an answer that smuggles in markup cannot run even if a page forgot to escape it.
SECURITY_HEADERS = [
    (
        b"content-security-policy",
        b"default-src 'self'; img-src 'self' data:; script-src 'self'; style-src 'self'; "
        b"connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'self'",
    ),
    (b"x-content-type-options", b"nosniff"),
    (b"x-frame-options", b"DENY"),
    (b"referrer-policy", b"no-referrer"),
    (b"cache-control", b"no-store"),
]


class TokenBucket:
    """``rate`` requests per second on average, up to ``burst`` at once."""

    def __init__(self, rate: float, burst: int) -> None:
        self.rate = rate
        self.burst = float(burst)
        self.tokens = float(burst)
        self.stamp = time.monotonic()

    def take(self) -> bool:
        now = time.monotonic()
        self.tokens = min(self.burst, self.tokens + (now - self.stamp) * self.rate)
        self.stamp = now
        if self.tokens < 1.0:
            return False
        self.tokens -= 1.0
        return True


class RateLimit:
    """ASGI middleware: a token bucket per client address and page (429 when it runs dry),
    and the security headers on every response.

    A page is told by its session code, so participants behind one address do not share a
    bucket; but only a code that ``known_code`` accepts (one the server issued) gets a bucket
    of its own. Any other code, like no code, shares the address's bucket, so a client cannot
    mint fresh buckets by sending made-up codes. Buckets of the least recently seen clients
    are dropped beyond ``max_clients``, so the table stays bounded."""

    def __init__(
        self,
        app: ASGIApp,
        rate: float,
        burst: int,
        known_code: Callable[[str], bool] = lambda code: False,
        max_clients: int = 4096,
    ) -> None:
        self.app = app
        self.rate = rate
        self.burst = burst
        self.known_code = known_code
        self.max_clients = max_clients
        self._buckets: dict[str, TokenBucket] = {}

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = list(message.get("headers", [])) + SECURITY_HEADERS
            await send(message)

        client = scope.get("client")
        code = dict(scope["headers"]).get(b"x-session-code", b"")[:64].decode("latin-1")
        page = code if code and self.known_code(code) else ""
        address = f"{client[0] if client else '?'} {page}"
        bucket = self._buckets.pop(address, None) or TokenBucket(self.rate, self.burst)
        self._buckets[address] = bucket  # most recently seen last
        while len(self._buckets) > self.max_clients:
            del self._buckets[next(iter(self._buckets))]
        if not bucket.take():
            reply = error_response(
                429,
                "too many requests",
                "slow down and try again in a second",
                **{"Retry-After": "1"},
            )
            await reply(scope, receive, send_with_headers)
            return
        await self.app(scope, receive, send_with_headers)
