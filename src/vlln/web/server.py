"""Running the web app with uvicorn (``vlln serve web``).

Loopback by default. The oracle page shows where targets are and the lobby starts sessions,
so serving beyond this machine requires a token: without one the server refuses to start.
"""

from __future__ import annotations

import sys
from pathlib import Path

import uvicorn

from vlln.errors import ConfigError
from vlln.http.addresses import is_loopback
from vlln.http.server import uvicorn_server
from vlln.web.app import create_app, open_store
from vlln.web.config import DEFAULT_HOST, DEFAULT_PORT, WebConfig


def build_server(
    config: WebConfig,
    host: str = DEFAULT_HOST,
    port: int = DEFAULT_PORT,
    *,
    source: str = "",
    log_level: str = "warning",
) -> uvicorn.Server:
    """A uvicorn server for the web app, not yet running (its output folder already taken);
    ``port=0`` picks a free port."""
    if not is_loopback(host):
        if config.token is None:
            raise ConfigError(
                f"host {host!r} is not a loopback address; serving the study beyond this "
                "machine needs an access token: set VLLN_WEB_TOKEN (16+ characters)"
            )
        print(
            f"warning: the vlln web app will listen on {host}:{port}, reachable from other "
            "machines; starting sessions needs the token, each page its session code",
            file=sys.stderr,
        )
    return uvicorn_server(
        lambda: create_app(config, source, open_store(config, source)),
        host,
        port,
        log_level,
        timeout_graceful_shutdown=5,
    )


def serve(config: WebConfig, host: str, port: int, source: str) -> None:
    """Serve until interrupted; prints the address of the lobby."""
    server = build_server(config, host, port, source=source)
    shown = f"[{host}]" if ":" in host else host
    print(
        f"vlln web: lobby at http://{shown}:{port}/ ; records in {config.out}",
        file=sys.stderr,
    )
    server.run()


def episode_source(episode_file: Path | None, split: str, houses: int) -> str:
    """How ``web.json`` names the served episodes."""
    if episode_file is not None:
        return f"file {episode_file.resolve()}"
    return f"split {split}, {houses} houses"
