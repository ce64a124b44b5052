"""Running the oracle service with uvicorn (``vlln oracle serve``).

The server listens on loopback unless told otherwise: the oracle hands out privileged
knowledge of the house (where the target is), so exposing it on a network is a deliberate
choice, made with ``allow_remote=True`` and a bearer token (refused without one), and
announced with a warning on stderr.
"""

from __future__ import annotations

import gc
import os
import sys

import uvicorn

from vlln.errors import ConfigError
from vlln.http.addresses import is_loopback
from vlln.http.server import uvicorn_server
from vlln.oracle_service.app import create_app
from vlln.oracle_service.config import (
    DEFAULT_HOST,
    DEFAULT_PORT,
    DEFAULT_TOKEN_ENV,
    ServiceConfig,
)


def token_from_environment(token_env: str | None) -> str | None:
    """The bearer token: a variable named with --token-env must hold one; without the flag,
    VLLN_ORACLE_TOKEN is used when it is set (and must then not be empty)."""
    name = token_env or DEFAULT_TOKEN_ENV
    value = os.environ.get(name)
    if value is None and token_env is None:
        return None
    if not value or not value.strip():
        state = "is not set" if value is None else "is empty"
        raise ConfigError(
            f"the token variable {name} {state}; export {name}=<token> before starting the "
            "service, or leave out --token-env to serve loopback without a token"
        )
    return value


def build_server(
    config: ServiceConfig,
    host: str = DEFAULT_HOST,
    port: int = DEFAULT_PORT,
    *,
    allow_remote: bool = False,
    log_level: str = "info",
) -> uvicorn.Server:
    """A uvicorn server for the oracle app, not yet running; ``port=0`` picks a free port."""
    if not is_loopback(host):
        if not allow_remote:
            raise ConfigError(
                f"host {host!r} is not a loopback address; the oracle reveals where targets "
                "are, so serving it beyond this machine needs allow_remote=True "
                "(--allow-remote), ideally with a token"
            )
        if not config.token:
            raise ConfigError(
                f"host {host!r} is reachable from other machines, so the oracle needs a bearer "
                "token there: export VLLN_ORACLE_TOKEN=<token> (or name a variable with "
                "--token-env)"
            )
        print(
            f"warning: the vlln oracle will listen on {host}:{port}, reachable from other "
            "machines, with a bearer token",
            file=sys.stderr,
        )
    return uvicorn_server(lambda: create_app(config), host, port, log_level)


def freeze_startup_objects() -> int:
    """Leave every object alive now (the imported code, the app) out of the garbage
    collector's full passes and return how many there are. They live as long as the process
    anyway, and scanning them made each full pass stall every request for ~100 ms of CPU;
    without them a pass scans only the houses and sessions (~20 ms)."""
    gc.collect()
    gc.freeze()
    return gc.get_freeze_count()


def serve(
    config: ServiceConfig, host: str, port: int, *, allow_remote: bool, log_level: str
) -> None:
    """Serve the oracle of ``config`` until interrupted."""
    server = build_server(config, host, port, allow_remote=allow_remote, log_level=log_level)
    freeze_startup_objects()
    server.run()
