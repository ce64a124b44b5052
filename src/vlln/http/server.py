"""The uvicorn server both applications run in: no proxy headers trusted (the client's
address is the socket's, which the rate and build limits count by), no server banner, and
the application's lifespan run so it can open and close what it owns."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import uvicorn

from vlln.errors import ConfigError
from vlln.http.addresses import check_port

LOG_LEVELS = ("critical", "error", "warning", "info", "debug")


def uvicorn_server(
    make_app: Callable[[], Any], host: str, port: int, log_level: str, **settings: Any
) -> uvicorn.Server:
    """A server for the application ``make_app`` builds, not yet running; ``port=0`` picks a
    free port. The port and log level are checked before the application is built (building
    one may take an output folder). ``settings`` are further ``uvicorn.Config`` arguments."""
    check_port(port)
    if log_level not in LOG_LEVELS:
        raise ConfigError(f"log_level must be one of {', '.join(LOG_LEVELS)}, got {log_level!r}")
    config = uvicorn.Config(
        make_app(),
        host=host,
        port=port,
        log_level=log_level,
        proxy_headers=False,
        server_header=False,
        lifespan="on",
        **settings,
    )
    return uvicorn.Server(config)
