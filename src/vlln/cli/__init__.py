"""Command-line entry points. Each command parses its arguments and calls one library function;
errors raised on purpose (vlln.errors.VllnError) are printed as one line, not a traceback.
One module per command group; each adds its subcommands to the parser."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence

from vlln.cli.bench import add_bench_commands
from vlln.cli.data import add_data_commands
from vlln.cli.evaluation import add_demo_command, add_eval_commands, add_video_command
from vlln.cli.oracle import add_oracle_commands
from vlln.cli.serve import add_serve_commands
from vlln.cli.train import add_train_commands
from vlln.cli.world import add_world_commands
from vlln.errors import VllnError

Handler = Callable[[argparse.Namespace], int]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="vlln", description="VL-LN Bench: navigation agents that talk, on a CPU simulator."
    )
    commands = parser.add_subparsers(dest="command", required=True)
    add_world_commands(commands)
    add_bench_commands(commands)
    add_demo_command(commands)
    add_eval_commands(commands)
    add_oracle_commands(commands)
    add_data_commands(commands)
    add_serve_commands(commands)
    add_video_command(commands)
    add_train_commands(commands)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    handler: Handler = args.handler
    try:
        return handler(args)
    except VllnError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(
            "interrupted; what finished is kept: run the same command again to resume",
            file=sys.stderr,
        )
        return 130
