"""``vlln oracle ...``: serve the oracle, measure its classifier."""

from __future__ import annotations

from typing import TYPE_CHECKING

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands
from vlln.extras import SERVE_PACKAGES, require_extra

if TYPE_CHECKING:
    from vlln.cli.oracle_settings import ClassifyReportCommand, ServeCommand


def _serve_command() -> type[ServeCommand]:
    from vlln.cli.oracle_settings import ServeCommand

    return ServeCommand


def _classify_report_command() -> type[ClassifyReportCommand]:
    from vlln.cli.oracle_settings import ClassifyReportCommand

    return ClassifyReportCommand


def _oracle_serve(command: ServeCommand) -> int:
    require_extra("serve", "vlln oracle serve", SERVE_PACKAGES)
    from vlln.oracle_service.config import ServiceConfig, ServiceLimits
    from vlln.oracle_service.server import serve, token_from_environment
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


def _oracle_classify_report(command: ClassifyReportCommand) -> int:
    from vlln.oracle.question_set import classifier_report

    accuracy, table = classifier_report(command.questions)
    print(f"accuracy: {accuracy:.1%}\n\n{table}")
    return 0


def add_oracle_commands(commands: Commands) -> None:
    oracle = commands.add_parser("oracle", help="the oracle").add_subparsers(
        dest="oracle_command", required=True
    )
    add_config_command(
        oracle, "serve", _serve_command, _oracle_serve, help="answer questions over HTTP (FastAPI)"
    )
    add_config_command(
        oracle,
        "classify-report",
        _classify_report_command,
        _oracle_classify_report,
        help="accuracy and confusion matrix of the offline classifier",
    )
