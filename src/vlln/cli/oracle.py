"""``vlln oracle ...``: serve the oracle, measure its classifier."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Annotated

from pydantic import Field, field_validator

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands
from vlln.extras import SERVE_PACKAGES, require_extra
from vlln.oracle.service.config import (
    DEFAULT_HOST,
    DEFAULT_PORT,
    LOG_LEVELS,
    ServiceConfig,
    ServiceLimits,
)


class ServeCommand(ServiceLimits):
    """``vlln oracle serve``: the service's limits and where and how it listens."""

    host: str = DEFAULT_HOST
    """address to listen on (loopback only unless --allow-remote)"""
    port: Annotated[int, Field(ge=0, le=65535)] = DEFAULT_PORT
    """port (0: a free one)"""
    token_env: str | None = None
    """environment variable holding the bearer token; it must be set and not empty (none:
    VLLN_ORACLE_TOKEN when set, else no token, loopback only)"""
    episodes: Path | None = None
    """an episode file whose episodes sessions can name"""
    allow_remote: bool = False
    """allow a host other than loopback"""
    log_level: str = "warning"
    """uvicorn log level (warning: no line per request)"""

    @field_validator("log_level")
    @classmethod
    def _known_level(cls, value: str) -> str:
        if value not in LOG_LEVELS:
            raise ValueError(f"must be one of {', '.join(LOG_LEVELS)}, got {value!r}")
        return value


def _oracle_serve(command: ServeCommand) -> int:
    require_extra("serve", "vlln oracle serve", SERVE_PACKAGES)
    from vlln.oracle.service.server import serve, token_from_environment
    from vlln.tasks.episode import read_episodes

    limits = command.model_dump(include=set(ServiceLimits.model_fields))
    config = ServiceConfig.build(
        {
            **limits,
            "token": token_from_environment(command.token_env),
            "episodes": () if command.episodes is None else tuple(read_episodes(command.episodes)),
        },
        flags=False,
    )
    serve(
        config,
        command.host,
        command.port,
        allow_remote=command.allow_remote,
        log_level=command.log_level,
    )
    return 0


def _oracle_classify_report(args: argparse.Namespace) -> int:
    from vlln.oracle.question_set import classifier_report

    accuracy, table = classifier_report(args.questions)
    print(f"accuracy: {accuracy:.1%}\n\n{table}")
    return 0


def add_oracle_commands(commands: Commands) -> None:
    oracle = commands.add_parser("oracle", help="the oracle").add_subparsers(
        dest="oracle_command", required=True
    )
    add_config_command(
        oracle, "serve", ServeCommand, _oracle_serve, help="answer questions over HTTP (FastAPI)"
    )
    report = oracle.add_parser(
        "classify-report", help="accuracy and confusion matrix of the offline classifier"
    )
    report.add_argument("--questions", help="a JSON Lines question set (default: held-out set)")
    report.set_defaults(handler=_oracle_classify_report)
