"""Command-line entry points. Each command parses its arguments and calls one library function;
errors raised on purpose (vlln.errors.VllnError) are printed as one line, not a traceback."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from vlln.errors import ConfigError, VllnError

Handler = Callable[[argparse.Namespace], int]


def _world_show(args: argparse.Namespace) -> int:
    from vlln.viz.show import show_world
    from vlln.world.generator import parameters_from_overrides

    params = parameters_from_overrides(args.param)
    files = show_world(args.seed, Path(args.out), n_views=args.views, params=params)
    print(f"wrote {len(files)} images to {args.out} (map: {files[0]})")
    return 0


def _bench_sim(args: argparse.Namespace) -> int:
    from vlln.bench.sim import run_sim_benchmark

    run_sim_benchmark(seed=args.seed, frames=args.frames, repeats=args.repeats, as_json=args.json)
    return 0


def _demo(args: argparse.Namespace) -> int:
    from vlln.demo import run_demo

    run_demo(Path(args.out))
    return 0


def _eval(args: argparse.Namespace) -> int:
    from vlln.eval.config import EvalConfig, default_budgets, parse_budgets
    from vlln.eval.runner import run_evaluation
    from vlln.eval.sharding import Shard

    if args.budgets is not None:
        budgets = parse_budgets(args.budgets)
    elif args.budget is not None:
        budgets = (args.budget,)
    else:
        budgets = default_budgets(args.task)
    episode_file = None if args.episode_file is None else str(Path(args.episode_file).resolve())
    config = EvalConfig(
        agent=args.agent,
        task=args.task,
        split=None if episode_file else args.split,
        episode_file=episode_file,
        episodes=args.episodes,
        budgets=budgets,
        seed=args.seed,
        houses=args.houses,
        shard=Shard.parse(args.shard),
        max_steps=args.max_steps,
    )
    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    outcome = run_evaluation(
        config,
        Path(args.out),
        cache_dir=cache_dir,
        stop_after=args.stop_after,
        progress=not args.quiet,
    )
    state = "complete" if outcome.complete else "incomplete: rerun the same command to go on"
    for line in outcome.repaired:
        print(f"repaired: {line.describe()}", file=sys.stderr)
    print(
        f"{len(outcome.records)} of {outcome.planned} episodes in {args.out} ({state}); "
        f"played {outcome.played} in {outcome.seconds:.1f} s",
        file=sys.stderr,
    )
    print(outcome.health.line(), file=sys.stderr)
    if outcome.summary is not None:
        print((Path(args.out) / "summary.md").read_text(encoding="utf-8"), end="")
    return 0


def _score(args: argparse.Namespace) -> int:
    import json

    from vlln.eval.health import run_health
    from vlln.eval.results import load_runs
    from vlln.eval.summary import summarize_run, summary_json, summary_markdown

    contents = load_runs(Path(path) for path in args.dirs)
    health = run_health(contents)
    print(health.line(), file=sys.stderr)
    groups = summarize_run(contents.records, args.success_radius, args.os_radius)
    if args.json:
        data = summary_json(groups) | {"health": health.to_json()}
        print(json.dumps(data, indent=2, allow_nan=False))
    else:
        markdown = summary_markdown(groups, "Scores of " + ", ".join(args.dirs))
        print(markdown + f"\n{health.line()}\n", end="")
    return 0


def _report(args: argparse.Namespace) -> int:
    from vlln.eval.report import write_report

    dirs = [Path(path) for path in args.dirs]
    out = Path(args.out) if args.out else (dirs[0] / "report" if len(dirs) == 1 else Path("report"))
    files = write_report(
        dirs,
        out,
        samples_per_run=args.samples,
        success_radius=args.success_radius,
        os_radius=args.os_radius,
    )
    print(f"wrote {len(files)} files to {out}: {out / 'report.md'} and {out / 'report.html'}")
    return 0


def _bench_eval(args: argparse.Namespace) -> int:
    from vlln.bench.eval import run_eval_benchmark

    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    run_eval_benchmark(episodes=args.episodes, as_json=args.json, cache_dir=cache_dir)
    return 0


def _add_eval_commands(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`vlln eval`, `vlln score` and `vlln report`."""
    from vlln.tasks.metrics import ORACLE_SUCCESS_RADIUS, SUCCESS_RADIUS

    run = commands.add_parser("eval", help="play an agent over episodes into a run directory")
    run.add_argument("--agent", required=True, help="agent name (random, expert, frontier, ...)")
    run.add_argument("--task", required=True, help="iign, ign or objectnav")
    source = run.add_mutually_exclusive_group()
    source.add_argument("--split", default="test", help="built-in split (default test)")
    source.add_argument("--episode-file", help="released-format episode file (.json.gz)")
    run.add_argument("--episodes", type=int, help="first N episodes (default: all)")
    budget = run.add_mutually_exclusive_group()
    budget.add_argument("--budget", type=int, help="dialog budget (default 5 on IIGN, else 0)")
    budget.add_argument("--budgets", help="several budgets, e.g. 0-5 or 0,5 (SR per budget, MSP)")
    run.add_argument("--out", required=True, help="run directory (resumed when it exists)")
    run.add_argument("--shard", default="0/1", help="i/n: every episode whose index mod n is i")
    run.add_argument("--seed", type=int, default=0, help="base seed of agents and oracle")
    run.add_argument("--houses", type=int, help="houses of the split (default: 61/15/14)")
    run.add_argument("--max-steps", type=int, default=500, help="counted-step cap (default 500)")
    run.add_argument("--cache-dir", help="where built splits are kept (default ~/.cache/vlln)")
    run.add_argument("--stop-after", type=int, help="play at most N episodes now, then stop")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.set_defaults(handler=_eval)

    score = commands.add_parser("score", help="recompute every metric from run directories")
    score.add_argument("dirs", nargs="+", help="run directories (e.g. the shards of one run)")
    score.add_argument("--json", action="store_true", help="print the summary as JSON")
    report = commands.add_parser("report", help="report.md and report.html of run directories")
    report.add_argument("dirs", nargs="+", help="run directories, compared side by side")
    report.add_argument("--out", help="report directory (default DIR/report for one run)")
    report.add_argument("--samples", type=int, default=4, help="episode maps per run (default 4)")
    for command in (score, report):
        command.add_argument(
            "--os-radius",
            type=float,
            default=ORACLE_SUCCESS_RADIUS,
            help=f"oracle-success radius in m (default {ORACLE_SUCCESS_RADIUS}, the reference's)",
        )
        command.add_argument(
            "--success-radius",
            type=float,
            default=SUCCESS_RADIUS,
            help=f"success radius in m (default {SUCCESS_RADIUS})",
        )
    score.set_defaults(handler=_score)
    report.set_defaults(handler=_report)


def _oracle_serve(args: argparse.Namespace) -> int:
    from vlln.oracle.service.server import serve, token_from_environment

    token = token_from_environment(args.token_env)
    serve(
        host=args.host,
        port=args.port,
        token=token,
        episodes=None if args.episodes is None else Path(args.episodes),
        allow_remote=args.allow_remote,
        max_sessions=args.max_sessions,
        oracle_seed=args.oracle_seed,
        builds_per_minute=args.builds_per_minute,
        client_builds_per_minute=args.client_builds_per_minute,
        log_level=args.log_level,
    )
    return 0


def _oracle_classify_report(args: argparse.Namespace) -> int:
    from vlln.oracle.question_set import classifier_report

    accuracy, table = classifier_report(args.questions)
    print(f"accuracy: {accuracy:.1%}\n\n{table}")
    return 0


def _bench_oracle(args: argparse.Namespace) -> int:
    from vlln.bench.oracle import run_oracle_benchmark

    run_oracle_benchmark(
        seed=args.seed,
        questions=args.questions,
        as_json=args.json,
        service_scenes=args.service_scenes,
    )
    return 0


def _add_oracle_commands(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    oracle = commands.add_parser("oracle", help="the oracle").add_subparsers(
        dest="oracle_command", required=True
    )
    serve = oracle.add_parser("serve", help="answer questions over HTTP (FastAPI)")
    serve.add_argument("--host", default="127.0.0.1", help="address (default loopback only)")
    serve.add_argument("--port", type=int, default=8765, help="port (default 8765)")
    serve.add_argument(
        "--token-env",
        help="environment variable holding the bearer token; it must be set and not empty "
        "(without the flag: VLLN_ORACLE_TOKEN when set, else no token, loopback only)",
    )
    serve.add_argument("--episodes", help="an episode file whose episodes sessions can name")
    serve.add_argument(
        "--allow-remote", action="store_true", help="allow a host other than loopback"
    )
    serve.add_argument("--max-sessions", type=int, default=64, help="sessions kept (default 64)")
    serve.add_argument("--oracle-seed", type=int, default=0, help="paraphrase seed (default 0)")
    serve.add_argument(
        "--builds-per-minute", type=int, default=60, help="house builds, all clients (default 60)"
    )
    serve.add_argument(
        "--client-builds-per-minute",
        type=int,
        default=20,
        help="house builds one client address may cause (default 20)",
    )
    serve.add_argument(
        "--log-level",
        default="warning",
        help="uvicorn log level (default warning: no line per request)",
    )
    serve.set_defaults(handler=_oracle_serve)
    report = oracle.add_parser(
        "classify-report", help="accuracy and confusion matrix of the offline classifier"
    )
    report.add_argument("--questions", help="a JSON Lines question set (default: held-out set)")
    report.set_defaults(handler=_oracle_classify_report)


def _data_build(args: argparse.Namespace) -> int:
    from vlln.datagen.build import BuildConfig, build_dataset
    from vlln.datagen.cost import build_cost
    from vlln.eval.sharding import Shard

    config = BuildConfig(
        houses=args.houses, split=args.split, seed=args.seed, per_house=args.per_house
    )
    if Path(args.out).exists() and not Path(args.out).is_dir():
        raise ConfigError(f"--out {args.out} is a file, not a folder; give a dataset folder")
    shard = Shard.parse(args.shard) if args.shard else None
    houses = -(-config.houses // shard.count) if shard else config.houses
    cost = build_cost(houses, config.per_house)
    print(cost.line(), file=sys.stderr)
    if cost.large and not args.yes and sys.stdin.isatty():
        answer = input("this is a large build; start it? [y/N] ")
        if answer.strip().lower() not in ("y", "yes"):
            print("not started (pass --yes to skip this question)", file=sys.stderr)
            return 1
    out = build_dataset(Path(args.out), config, shard=shard, progress=not args.quiet)
    print(f"dataset in {out} (summarise it with: vlln data stats {out})")
    return 0


def _data_stats(args: argparse.Namespace) -> int:
    from vlln.datagen.stats.report import write_stats

    paths = write_stats(Path(args.dataset), Path(args.out) if args.out else None)
    print("wrote " + ", ".join(str(path) for path in paths))
    return 0


def _data_export_sft(args: argparse.Namespace) -> int:
    from vlln.datagen.sft.config import SftConfig
    from vlln.datagen.sft.export import export_sft

    config = SftConfig(budget=args.budget, history_frames=args.history)
    summary = export_sft(Path(args.dataset), Path(args.out), config, progress=not args.quiet)
    print(
        f"wrote {summary.samples} conversations from {summary.trajectories} trajectories "
        f"({summary.images} images) to {args.out}/sft.jsonl"
    )
    return 0


def _bench_data(args: argparse.Namespace) -> int:
    from vlln.bench.data import run_data_benchmark

    run_data_benchmark(houses=args.houses, per_house=args.per_house, as_json=args.json)
    return 0


def _add_data_commands(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    data = commands.add_parser("data", help="the training-data pipeline").add_subparsers(
        dest="data_command", required=True
    )
    build = data.add_parser(
        "build", help="scene summaries, episodes and dialog-augmented trajectories"
    )
    build.add_argument("--houses", type=int, required=True, help="houses of the split to use")
    build.add_argument("--out", required=True, help="dataset folder (a rerun resumes it)")
    build.add_argument(
        "--per-house",
        type=int,
        default=20,
        help="trajectories tried per house (default 20; 0 = every IIGN episode)",
    )
    build.add_argument("--split", default="train", help="house split (default train)")
    build.add_argument("--seed", type=int, default=0, help="seed of every random choice")
    build.add_argument("--shard", help="i/n: build every n-th house, starting at the i-th")
    build.add_argument("--quiet", action="store_true", help="no progress bars")
    build.add_argument(
        "--yes", action="store_true", help="start a large build without asking (it states its cost)"
    )
    build.set_defaults(handler=_data_build)
    stats = data.add_parser("stats", help="statistics, figure and report of a built dataset")
    stats.add_argument("dataset", help="a folder made by vlln data build")
    stats.add_argument("--out", help="where to write them (default DATASET/stats)")
    stats.set_defaults(handler=_data_stats)
    sft = data.add_parser(
        "export-sft", help="trajectories as multi-image conversations for fine-tuning"
    )
    sft.add_argument("dataset", help="a folder made by vlln data build")
    sft.add_argument("--out", required=True, help="output folder (sft.jsonl and images)")
    sft.add_argument("--budget", type=int, help="oracle answers per trajectory (default: all)")
    sft.add_argument("--history", type=int, default=8, help="history frames (default 8)")
    sft.add_argument("--quiet", action="store_true", help="no progress bar")
    sft.set_defaults(handler=_data_export_sft)


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
    show.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a house-generator parameter, e.g. --param max_rooms=6 (repeatable)",
    )
    show.set_defaults(handler=_world_show)

    bench = commands.add_parser("bench", help="speed and memory benchmarks").add_subparsers(
        dest="bench_command", required=True
    )
    sim = bench.add_parser("sim", help="renderer, motion and geodesic figures")
    sim.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    sim.add_argument("--frames", type=int, default=300, help="frames per timing (default 300)")
    sim.add_argument("--repeats", type=int, default=3, help="passes per frame rate (default 3)")
    sim.add_argument("--json", action="store_true", help="print one JSON object per line")
    sim.set_defaults(handler=_bench_sim)
    bench_eval = bench.add_parser("eval", help="episodes per hour of the evaluation runner")
    bench_eval.add_argument("--episodes", type=int, default=6, help="episodes (default 6)")
    bench_eval.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_eval.add_argument("--cache-dir", help="where built splits are kept")
    bench_eval.set_defaults(handler=_bench_eval)
    bench_oracle = bench.add_parser("oracle", help="answer latency of the offline oracle")
    bench_oracle.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    bench_oracle.add_argument(
        "--questions", type=int, default=2000, help="questions (default 2000)"
    )
    bench_oracle.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_oracle.add_argument(
        "--service-scenes",
        type=int,
        default=64,
        help="houses given a session each for the service's memory figure (default 64; "
        "0 = no service figures)",
    )
    bench_oracle.set_defaults(handler=_bench_oracle)

    bench_data = bench.add_parser("data", help="trajectories per hour of the data pipeline")
    bench_data.add_argument("--houses", type=int, default=2, help="training houses (default 2)")
    bench_data.add_argument(
        "--per-house", type=int, default=6, help="trajectories per house (default 6)"
    )
    bench_data.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_data.set_defaults(handler=_bench_data)

    demo = commands.add_parser("demo", help="the main job on the built-in houses")
    demo.add_argument("--out", default="out/demo", help="output directory (default out/demo)")
    demo.set_defaults(handler=_demo)
    _add_eval_commands(commands)
    _add_oracle_commands(commands)
    _add_data_commands(commands)
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
