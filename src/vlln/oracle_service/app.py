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
use it. :class:`vlln.http.gate.RequestGate` checks every request before it reaches a route,
so that a request without the token never gets its body parsed.
"""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator, Callable
from concurrent.futures import ThreadPoolExecutor
from contextlib import asynccontextmanager
from functools import partial
from typing import Any, TypeVar

from fastapi import FastAPI, Request, Response

from vlln import __version__
from vlln.http.gate import RequestGate
from vlln.http.responses import add_error_handlers
from vlln.oracle_service.config import ServiceConfig
from vlln.oracle_service.hosted_oracle import HostedOracle
from vlln.oracle_service.schemas import (
    AskRequest,
    AskResponse,
    CreateSessionRequest,
    CreateSessionResponse,
    ErrorBody,
    HealthResponse,
    SessionView,
)

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
    add_error_handlers(app)
    app.add_middleware(
        RequestGate,
        token=config.token,
        max_body_bytes=config.max_body_bytes,
        public_paths=PUBLIC_PATHS,
    )

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
