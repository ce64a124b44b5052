"""The request gate: every request is checked before it reaches a route, so that a request
without the token never gets its body parsed."""

from __future__ import annotations

import hmac
from collections.abc import Collection

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from vlln.http.responses import error_response


class RequestGate:
    """ASGI middleware: the bearer token (401; ``token=None`` serves without one, and
    ``public_paths`` never need it), the body size limit (413, or 400 for a malformed
    Content-Length) and a JSON content type for bodies (415), checked before a route sees the
    request. Requiring the JSON content type also keeps browsers' cross-site form posts
    (which cannot send it without a CORS preflight) away from the application."""

    def __init__(
        self,
        app: ASGIApp,
        token: str | None,
        max_body_bytes: int,
        public_paths: Collection[str] = (),
    ) -> None:
        self.app = app
        self.token = None if token is None else token.encode("utf-8")
        self.max_body_bytes = max_body_bytes
        self.public_paths = frozenset(public_paths)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v for k, v in scope["headers"]}
        token = self.token
        if (
            token is not None
            and scope["path"] not in self.public_paths
            and not bearer_matches(headers.get("authorization"), token)
        ):
            reply = error_response(
                401,
                "unauthorized",
                "send the header 'Authorization: Bearer <token>' with the server's token",
                **{"WWW-Authenticate": "Bearer"},
            )
            await reply(scope, receive, send)
            return
        declared = headers.get("content-length")
        if declared is not None:
            if not declared.isdigit():
                await error_response(400, "bad request", "Content-Length must be a number")(
                    scope, receive, send
                )
                return
            if int(declared) > self.max_body_bytes:
                await self._too_large(scope, receive, send)
                return
        body = bytearray()
        more = True
        while more:
            message = await receive()
            if message["type"] != "http.request":
                return  # the client went away before sending its body
            body += message.get("body", b"")
            more = bool(message.get("more_body", False))
            if len(body) > self.max_body_bytes:
                await self._too_large(scope, receive, send)
                return
        if body and not _is_json(headers.get("content-type", b"")):
            detail = "the body must be JSON, sent with the header 'Content-Type: application/json'"
            await error_response(415, "unsupported media type", detail)(scope, receive, send)
            return
        await self.app(scope, _replay(bytes(body), receive), send)

    async def _too_large(self, scope: Scope, receive: Receive, send: Send) -> None:
        detail = f"the request body is over the limit of {self.max_body_bytes} bytes"
        await error_response(413, "request body too large", detail)(scope, receive, send)


def bearer_matches(header: str | bytes | None, token: str | bytes) -> bool:
    """Whether an Authorization header is ``Bearer <token>`` (compared in constant time).
    A header given as text is encoded as latin-1, the encoding HTTP headers arrive in."""
    raw = header.encode("latin-1", "replace") if isinstance(header, str) else (header or b"")
    secret = token.encode("utf-8") if isinstance(token, str) else token
    scheme, _, credentials = raw.partition(b" ")
    return scheme.lower() == b"bearer" and hmac.compare_digest(credentials.strip(), secret)


def _is_json(content_type: bytes) -> bool:
    """Whether a Content-Type names JSON (``application/json`` or ``application/*+json``)."""
    media = content_type.split(b";")[0].strip().lower()
    return media == b"application/json" or (
        media.startswith(b"application/") and media.endswith(b"+json")
    )


def _replay(body: bytes, receive: Receive) -> Receive:
    """A receive callable that first hands out the already read body, then defers to the
    server's (which reports a disconnect)."""
    sent = False

    async def replayed() -> Message:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replayed
