"""Command-line entry points. Each command parses its arguments and calls one library function;
errors raised on purpose (vlln.errors.VllnError) are printed as one line, not a traceback."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from vlln.errors import VllnError

Handler = Callable[[argparse.Namespace], int]


def _world_show(args: argparse.Namespace) -> int:
    from vlln.viz.show import show_world

    files = show_world(args.seed, Path(args.out), n_views=args.views)
    print(f"wrote {len(files)} images to {args.out} (map: {files[0]})")
    return 0


def _bench_sim(args: argparse.Namespace) -> int:
    from vlln.bench.sim import run_sim_benchmark

    run_sim_benchmark(seed=args.seed, frames=args.frames, as_json=args.json)
    return 0


def _demo(args: argparse.Namespace) -> int:
    from vlln.demo import run_demo

    run_demo(Path(args.out))
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="vlln", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)

    world = commands.add_parser("world", help="procedural houses").add_subparsers(
        dest="world_command", required=True
    )
    show = world.add_parser("show", help="write a top-down map and egocentric views of a house")
    show.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    show.add_argument("--out", required=True, help="output directory")
    show.add_argument("--views", type=int, default=4, help="number of rooms to view (default 4)")
    show.set_defaults(handler=_world_show)

    bench = commands.add_parser("bench", help="speed and memory benchmarks").add_subparsers(
        dest="bench_command", required=True
    )
    sim = bench.add_parser("sim", help="renderer, motion and geodesic figures")
    sim.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    sim.add_argument("--frames", type=int, default=300, help="frames per timing (default 300)")
    sim.add_argument("--json", action="store_true", help="print one JSON object per line")
    sim.set_defaults(handler=_bench_sim)

    demo = commands.add_parser("demo", help="the main job on the built-in houses")
    demo.add_argument("--out", default="out/demo", help="output directory (default out/demo)")
    demo.set_defaults(handler=_demo)
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
        print("interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
