"""The oracle over HTTP: a FastAPI application built by :func:`create_app`.

Endpoints (JSON in and out; errors are ``{"error": ..., "detail": ...}``):

* ``POST /v1/sessions`` start a dialog about a target (scene + instance, or an episode id);
* ``POST /v1/sessions/{id}/ask`` ask a question from a pose; the server renders the view;
* ``GET /v1/sessions/{id}`` the dialog so far; ``DELETE /v1/sessions/{id}`` end it;
* ``GET /v1/health`` liveness, never behind the token;
* ``GET /docs`` interactive documentation; ``GET /v1/openapi.json`` the machine-readable
  description, for generating clients (neither is behind the token: they hold no house data).

Every piece of state lives in the application object, so two apps never share anything.
Requests are served concurrently: those that touch no house (health, showing and deleting a
session) are answered on the event loop at once, while creating sessions and answering
questions (house builds, rendering, the oracle) run on one worker thread, which keeps every
OpenGL context on the thread that uses it; the session store is locked, so both sides may
use it. :class:`RequestGate` checks every request
before it reaches a route, so that a request without the token never gets its body parsed.
"""

from __future__ import annotations

import asyncio
import hmac
from collections.abc import AsyncIterator, Callable
from concurrent.futures import ThreadPoolExecutor
from contextlib import asynccontextmanager
from functools import partial
from http import HTTPStatus
from typing import Any, TypeVar

from fastapi import FastAPI, Request, Response
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from vlln import __version__
from vlln.oracle.service.config import ServiceConfig
from vlln.oracle.service.hosted_oracle import HostedOracle
from vlln.oracle.service.schemas import (
    AskRequest,
    AskResponse,
    CreateSessionRequest,
    CreateSessionResponse,
    ErrorBody,
    HealthResponse,
    SessionView,
)
from vlln.oracle.service.sessions import ServiceError

HEALTH_PATH = "/v1/health"
DOCS_PATH = "/docs"
OPENAPI_PATH = "/v1/openapi.json"
PUBLIC_PATHS = (HEALTH_PATH, DOCS_PATH, OPENAPI_PATH)  # never behind the token: no house data
T = TypeVar("T")
_ERRORS: dict[int | str, dict[str, Any]] = {
    code: {"model": ErrorBody} for code in (400, 401, 404, 413, 415, 422, 429)
}


def create_app(config: ServiceConfig) -> FastAPI:
    """A new application serving the oracle with ``config``; it owns its sessions and scenes."""
    hosted = HostedOracle(config)
    worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="vlln-oracle")

    async def run(call: Callable[..., T], *args: Any) -> T:
        return await asyncio.get_running_loop().run_in_executor(worker, partial(call, *args))

    @asynccontextmanager
    async def lifespan(_: FastAPI) -> AsyncIterator[None]:
        yield
        await run(hosted.close)
        worker.shutdown(wait=True)

    app = FastAPI(
        title="vlln oracle",
        version=__version__,
        summary="Answers a navigator's questions about its target in a vlln house.",
        docs_url=DOCS_PATH,
        redoc_url=None,
        openapi_url=OPENAPI_PATH,
        lifespan=lifespan,
    )
    _add_error_handlers(app)
    app.add_middleware(RequestGate, token=config.token, max_body_bytes=config.max_body_bytes)

    @app.get(HEALTH_PATH)
    async def health() -> HealthResponse:
        return hosted.health()

    @app.post("/v1/sessions", status_code=201, responses=_ERRORS)
    async def create_session(request: CreateSessionRequest, http: Request) -> CreateSessionResponse:
        return await run(hosted.create, request, _client(http))

    @app.post("/v1/sessions/{session_id}/ask", responses=_ERRORS)
    async def ask(session_id: str, request: AskRequest, http: Request) -> AskResponse:
        return await run(hosted.ask, session_id, request, _client(http))

    @app.get("/v1/sessions/{session_id}", responses=_ERRORS)
    async def show_session(session_id: str) -> SessionView:
        return hosted.view(session_id)

    @app.delete("/v1/sessions/{session_id}", status_code=204, responses=_ERRORS)
    async def delete_session(session_id: str) -> Response:
        hosted.delete(session_id)
        return Response(status_code=204)

    return app


def _client(request: Request) -> str:
    """Who is charged for house builds: the client's address."""
    return request.client.host if request.client is not None else "unknown"


def error_response(status: int, error: str, detail: Any, **headers: str) -> JSONResponse:
    return JSONResponse({"error": error, "detail": detail}, status_code=status, headers=headers)


def _add_error_handlers(app: FastAPI) -> None:
    @app.exception_handler(ServiceError)
    async def service_error(_: Request, exc: ServiceError) -> JSONResponse:
        return error_response(exc.status, exc.error, exc.detail)

    @app.exception_handler(RequestValidationError)
    async def invalid_request(_: Request, exc: RequestValidationError) -> JSONResponse:
        problems = exc.errors()
        if any(problem.get("type") == "json_invalid" for problem in problems):
            return error_response(
                400, "malformed JSON", "the request body is not valid JSON; send a JSON object"
            )
        detail = [
            {
                "field": ".".join(str(part) for part in problem.get("loc", ())),
                "problem": problem.get("msg", ""),
            }
            for problem in problems
        ]
        return error_response(422, "invalid request", detail)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(_: Request, exc: StarletteHTTPException) -> JSONResponse:
        phrase = HTTPStatus(exc.status_code).phrase.lower()
        return error_response(exc.status_code, phrase, exc.detail, **(exc.headers or {}))

    @app.exception_handler(Exception)
    async def unexpected(_: Request, exc: Exception) -> JSONResponse:
        return error_response(500, "internal error", type(exc).__name__)


class RequestGate:
    """ASGI middleware: the bearer token (401), the body size limit (413, or 400 for a
    malformed Content-Length) and a JSON content type for bodies (415), checked before a
    route sees the request. Requiring the JSON content type also keeps browsers' cross-site
    form posts (which cannot send it without a CORS preflight) away from the oracle."""

    def __init__(self, app: ASGIApp, token: str | None, max_body_bytes: int) -> None:
        self.app = app
        self.token = None if token is None else token.encode("utf-8")
        self.max_body_bytes = max_body_bytes

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v for k, v in scope["headers"]}
        token = self.token
        if (
            token is not None
            and scope["path"] not in PUBLIC_PATHS
            and not _authorised(headers.get("authorization"), token)
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


def _is_json(content_type: bytes) -> bool:
    """Whether a Content-Type names JSON (``application/json`` or ``application/*+json``)."""
    media = content_type.split(b";")[0].strip().lower()
    return media == b"application/json" or (
        media.startswith(b"application/") and media.endswith(b"+json")
    )


def _authorised(header: bytes | None, token: bytes) -> bool:
    """Whether an Authorization header carries the token (constant-time comparison)."""
    scheme, _, credentials = (header or b"").partition(b" ")
    return scheme.lower() == b"bearer" and hmac.compare_digest(credentials.strip(), token)


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
