"""The web app: pages, and the JSON API they speak (FastAPI).

* ``GET /`` the lobby (create a session, join one with a code); ``/navigate`` and ``/answer``
  the two role pages. A page carries its code in the URL fragment (``/navigate#CODE``), which
  browsers never send to the server, and sends it in the ``X-Session-Code`` header.
* ``GET /api/lobby`` episodes and choices; ``POST /api/sessions`` create one: both need the
  bearer token when the server has one. ``POST /api/join`` says which page a code opens.
* ``GET /api/navigator`` and ``GET /api/oracle`` a role's view; with ``?after=VERSION`` they
  wait (up to 20 s) for something newer. ``POST /api/navigator/act``, ``/api/navigator/ask``,
  ``/api/oracle/answer``; ``GET /api/oracle/map`` the house map with the target.
  ``POST /api/navigator/end``: a person leaves the episode, recorded as abandoned, and its
  slot among the live sessions is free at once.

Bodies are bounded (:class:`vlln.http.gate.RequestGate`), errors are JSON error bodies
(:mod:`vlln.http.responses`), requests are rate-limited per client and every response carries
a strict Content-Security-Policy (:mod:`.limits`).
"""

from __future__ import annotations

import asyncio
import queue
from collections.abc import AsyncIterator, Callable
from concurrent.futures import Future
from contextlib import asynccontextmanager, suppress
from importlib import resources
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Header, Request
from fastapi.responses import FileResponse
from fastapi.staticfiles import StaticFiles

from vlln import __version__
from vlln.errors import ConfigError
from vlln.http.gate import RequestGate, bearer_matches
from vlln.http.responses import RequestError, add_error_handlers
from vlln.tasks.spec import Talk
from vlln.web.config import HUMAN_PREFIX, OracleKind, WebConfig
from vlln.web.limits import RateLimit
from vlln.web.oracles import oracle_factory
from vlln.web.schemas import ACTIONS, Act, Answer, Ask, CreateSession, Join
from vlln.web.session import EpisodeSession, Status
from vlln.web.store import NAVIGATOR, ORACLE, SessionStore
from vlln.web.views import navigator_view, oracle_map, oracle_view

LONG_POLL_S = 20.0
ACTION_WAIT_S = 10.0
QUESTION_WAIT_S = 1.0  # a person's answer takes longer: the page waits for it by polling
STATIC = Path(str(resources.files("vlln.web") / "static"))


class WebError(RequestError):
    """A request the web app cannot serve; ``status`` is its HTTP status code."""


def create_app(config: WebConfig, source: str = "", opened: SessionStore | None = None) -> FastAPI:
    """A new web app serving ``config`` with the store ``opened`` (see :func:`open_store`),
    or with one it opens (and resumes) when the app starts; it closes the store at the end."""
    holder: dict[str, SessionStore] = {}

    @asynccontextmanager
    async def lifespan(_: FastAPI) -> AsyncIterator[None]:
        store = opened
        if store is None:
            store = await asyncio.to_thread(open_store, config, source)
        store.attach(asyncio.get_running_loop())
        holder["store"] = store
        try:
            yield
        finally:
            await asyncio.to_thread(store.close)

    def store() -> SessionStore:
        return holder["store"]

    app = FastAPI(
        title="vlln web",
        version=__version__,
        docs_url=None,
        redoc_url=None,
        openapi_url=None,
        lifespan=lifespan,
    )
    add_error_handlers(app)
    app.add_middleware(RequestGate, token=None, max_body_bytes=config.max_body_bytes)

    def known_code(code: str) -> bool:
        opened_store = holder.get("store")
        return opened_store is not None and opened_store.find(code) is not None

    app.add_middleware(
        RateLimit,
        rate=config.requests_per_second,
        burst=config.request_burst,
        known_code=known_code,
    )
    app.mount("/static", StaticFiles(directory=STATIC), name="static")

    for route, page in (
        ("/", "index.html"),
        ("/navigate", "navigate.html"),
        ("/answer", "answer.html"),
    ):
        app.add_api_route(route, _page(page), methods=["GET"], include_in_schema=False)

    def admin(authorization: str | None) -> None:
        if config.token is not None and not bearer_matches(authorization, config.token):
            raise WebError(401, "unauthorized", "this server needs its access token (ask the host)")

    def role(code: str | None, wanted: str) -> EpisodeSession:
        found = store().find(code or "")
        if found is None or found[1] != wanted:
            raise WebError(404, "unknown code", f"no {wanted} page has this code; check it")
        return found[0]

    @app.get("/api/health")
    async def health() -> dict[str, str]:
        return {"status": "ok", "version": __version__}

    @app.get("/api/lobby")
    async def lobby(authorization: str | None = Header(default=None)) -> dict[str, Any]:
        admin(authorization)
        return {
            "episodes": [
                {
                    "index": i,
                    "episode_id": e.episode_id,
                    "scene_id": e.scene_id,
                    "instruction": e.instruction.instruction_text,
                }
                for i, e in enumerate(config.episodes)
            ],
            "agents": list(config.agents),
            "oracles": [kind.value for kind in config.oracles],
            "budget": config.dialog_budget,
            "task": config.task.value,
            "sessions": store().overview(),
        }

    @app.post("/api/sessions", status_code=201)
    async def create(
        body: CreateSession, authorization: str | None = Header(default=None)
    ) -> dict[str, Any]:
        admin(authorization)
        navigator = body.navigator
        if navigator == HUMAN_PREFIX:
            navigator = f"{HUMAN_PREFIX}:{body.participant or 'anonymous'}"
        try:
            created = await asyncio.to_thread(
                store().create, navigator, OracleKind(body.oracle), body.episode_index
            )
        except ConfigError as error:
            raise WebError(409, "cannot start this session", str(error)) from None
        return {
            "session_id": created.session_id,
            "episode_index": created.episode_index,
            "navigator_code": created.navigator_code,
            "oracle_code": created.oracle_code,
        }

    @app.post("/api/join")
    async def join(body: Join) -> dict[str, str]:
        found = store().find(body.code)
        if found is None:
            raise WebError(404, "unknown code", "no session has this code; check it")
        page = "/navigate" if found[1] == NAVIGATOR else "/answer"
        return {"role": found[1], "page": page}

    @app.get("/api/navigator")
    async def navigator(
        request: Request, after: int = 0, x_session_code: str | None = Header(default=None)
    ) -> dict[str, Any]:
        session = role(x_session_code, NAVIGATOR)
        await _wait(session, after, request)
        return navigator_view(session)

    @app.post("/api/navigator/act")
    async def act(body: Act, x_session_code: str | None = Header(default=None)) -> dict[str, Any]:
        session = role(x_session_code, NAVIGATOR)
        await _play(session, ACTIONS[body.action], ACTION_WAIT_S)
        return navigator_view(session)

    @app.post("/api/navigator/ask")
    async def ask(body: Ask, x_session_code: str | None = Header(default=None)) -> dict[str, Any]:
        session = role(x_session_code, NAVIGATOR)
        text = body.question.strip()
        if not text or len(text) > config.max_question_chars:
            raise WebError(
                422, "invalid question", f"ask in 1 to {config.max_question_chars} characters"
            )
        await _play(session, Talk(text), QUESTION_WAIT_S)
        return navigator_view(session)

    @app.post("/api/navigator/end")
    async def end(x_session_code: str | None = Header(default=None)) -> dict[str, Any]:
        session = role(x_session_code, NAVIGATOR)
        if not session.done:
            await _hand(session, session.leave, ACTION_WAIT_S)
        return navigator_view(session)

    @app.get("/api/oracle")
    async def oracle(
        request: Request, after: int = 0, x_session_code: str | None = Header(default=None)
    ) -> dict[str, Any]:
        session = role(x_session_code, ORACLE)
        session.oracle_joined()
        await _wait(session, after, request)
        return oracle_view(session)

    @app.get("/api/oracle/map")
    async def house_map(x_session_code: str | None = Header(default=None)) -> dict[str, Any]:
        session = role(x_session_code, ORACLE)
        if not await asyncio.to_thread(session.ready.wait, ACTION_WAIT_S):
            raise WebError(503, "not ready", "the house is still being built; try again")
        return await asyncio.to_thread(oracle_map, session)

    @app.post("/api/oracle/answer")
    async def answer(
        body: Answer, x_session_code: str | None = Header(default=None)
    ) -> dict[str, Any]:
        session = role(x_session_code, ORACLE)
        text = body.answer.strip()
        if not text or len(text) > config.max_answer_chars:
            raise WebError(
                422, "invalid answer", f"answer in 1 to {config.max_answer_chars} characters"
            )
        if not session.board.give(body.number, text):
            raise WebError(409, "too late", "this question is no longer waiting for an answer")
        return oracle_view(session)

    return app


def open_store(config: WebConfig, source: str) -> SessionStore:
    """Take the output folder and resume what was in flight; raises :class:`ConfigError`
    (before any server starts) when the folder cannot be used."""
    store = SessionStore(config, oracle_factory(config), source)
    store.open()
    return store


async def _wait(session: EpisodeSession, after: int, request: Request) -> None:
    """Long polling: return when the session is newer than ``after``, after
    :data:`LONG_POLL_S`, or when the page went away (a closed tab holds nothing open)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + LONG_POLL_S
    while session.signal.version <= after and loop.time() < deadline:
        await session.signal.wait_beyond(after, min(1.0, deadline - loop.time()))
        if await request.is_disconnected():
            return


async def _play(session: EpisodeSession, output: Any, wait_s: float) -> None:
    """Hand a navigator's action to its session and wait (up to ``wait_s``) until played."""
    status = session.view.status
    if status != Status.PLAYING:
        raise WebError(409, "not your turn", f"the episode is {status}")
    await _hand(session, lambda: session.submit(output), wait_s)


async def _hand(
    session: EpisodeSession, command: Callable[[], Future[None]], wait_s: float
) -> None:
    """Queue a navigator's command and wait (up to ``wait_s``) until the session played it."""
    try:
        done = command()
    except queue.Full:
        raise WebError(429, "too many actions", "wait for the last action to be played") from None
    with suppress(TimeoutError):
        await asyncio.wait_for(asyncio.shield(asyncio.wrap_future(done)), wait_s)


def _page(name: str) -> Any:
    async def page() -> FileResponse:
        return FileResponse(STATIC / name, media_type="text/html")

    return page
