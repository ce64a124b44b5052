"""``vlln demo``, ``vlln eval``, ``vlln score``, ``vlln report`` and ``vlln video``."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from vlln.cli.options import Commands, add_preset_option, add_ray_options
from vlln.errors import ConfigError


def _demo(args: argparse.Namespace) -> int:
    from vlln.demo import run_demo

    run_demo(Path(args.out))
    return 0


def _eval(args: argparse.Namespace) -> int:
    from vlln.eval.config import EvalConfig, default_budgets, parse_budgets
    from vlln.eval.run_dir import summary_md_file
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
        agent_options=_agent_options(args),
        detector=args.detector,
        preset=args.preset,
        scenes=None if args.scenes is None else str(Path(args.scenes).resolve()),
    )
    from vlln.tasks.scenes import SceneCache

    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    if args.ray is not None:
        from vlln.cluster.evaluation import run_ray_evaluation
        from vlln.cluster.model_server import ServerStats, ServingOptions

        def report_servers(stats: list[ServerStats]) -> None:
            for server in stats:
                print(f"model server: {server.describe()}", file=sys.stderr)

        if args.scenes is not None:
            raise ConfigError("--scenes and --ray do not mix yet: evaluate scanned scenes locally")
        outcome = run_ray_evaluation(
            config,
            Path(args.out),
            address=args.ray or None,
            cache_dir=cache_dir,
            episodes_per_chunk=args.chunk,
            max_retries=args.retries,
            progress=not args.quiet,
            sweep=not args.no_sweep,
            serving=ServingOptions(args.model_cpus, args.model_gpus, args.model_batch),
            on_model_stats=report_servers,
        )
    else:
        scenes = SceneCache(scenes_dir=config.scenes)
        try:
            outcome = run_evaluation(
                config,
                Path(args.out),
                cache_dir=cache_dir,
                stop_after=args.stop_after,
                progress=not args.quiet,
                scenes=scenes,
                sweep=not args.no_sweep,
            )
        finally:
            scenes.close()
    state = "complete" if outcome.complete else "incomplete: rerun the same command to go on"
    for line in outcome.repaired:
        print(f"repaired: {line.describe()}", file=sys.stderr)
    refused = f", {outcome.health.refused} refused" if outcome.health.refused else ""
    print(
        f"{len(outcome.records)} of {outcome.planned} episodes in {args.out}{refused} "
        f"({state}); played {outcome.played} in {outcome.seconds:.1f} s",
        file=sys.stderr,
    )
    print(outcome.health.line(), file=sys.stderr)
    if outcome.summary is not None:
        print(summary_md_file(Path(args.out)).read_text(encoding="utf-8"), end="")
    calls = [call for record in outcome.records for call in record.model_calls]
    if calls and all(call.text is None for call in calls):
        first = " ".join(str(calls[0].error).split())[:200]
        print(
            f"error: all {len(calls)} model calls failed (the first: {first}); the "
            f"episodes in {args.out} measure the server, not the model: fix the server and "
            "rerun with a new --out",
            file=sys.stderr,
        )
        return 1
    return 0


def _agent_options(args: argparse.Namespace) -> dict[str, str]:
    """Options of agents that take them, from the flags given (see the eval parser)."""
    flags = {
        "base_url": args.base_url,
        "model": args.model,
        "api_key_env": args.api_key_env,
        "timeout_s": args.model_timeout,
        "max_retries": args.model_retries,
        "cache_dir": None if args.model_cache is None else str(Path(args.model_cache).resolve()),
        "device": args.device,
        "max_tokens": args.max_tokens,
    }
    return {name: str(value) for name, value in flags.items() if value is not None}


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
        videos_per_run=args.videos,
        scenes=Path(args.scenes) if args.scenes else None,
    )
    print(f"wrote {len(files)} files to {out}: {out / 'report.md'} and {out / 'report.html'}")
    return 0


def add_eval_commands(commands: Commands) -> None:
    """`vlln eval`, `vlln score` and `vlln report`."""
    from vlln.tasks.metrics import ORACLE_SUCCESS_RADIUS, SUCCESS_RADIUS

    run = commands.add_parser("eval", help="play an agent over episodes into a run directory")
    run.add_argument(
        "--agent",
        required=True,
        help="agent name (random, expert, frontier, ...) or your own class as "
        "package.module:Class (docs/own-agent.md)",
    )
    run.add_argument("--task", required=True, help="iign, ign or objectnav")
    source = run.add_mutually_exclusive_group()
    source.add_argument(
        "--split",
        default="test",
        help="built-in split: train, val, test (default) or test500 (the paper's 500 "
        "test episodes)",
    )
    source.add_argument("--episode-file", help="released-format episode file (.json.gz)")
    run.add_argument("--scenes", help="folder of scanned scenes (<scenes>/<scene>/) the file names")
    run.add_argument("--episodes", type=int, help="first N episodes (default: all)")
    budget = run.add_mutually_exclusive_group()
    budget.add_argument("--budget", type=int, help="dialog budget (default 5 on IIGN, else 0)")
    run.add_argument(
        "--detector",
        help="object detector of the frontier agent: truth (default, privileged) or noisy",
    )
    budget.add_argument("--budgets", help="several budgets, e.g. 0-5 or 0,5 (SR per budget, MSP)")
    run.add_argument("--out", required=True, help="run directory (resumed when it exists)")
    run.add_argument("--shard", default="0/1", help="i/n: every episode whose index mod n is i")
    run.add_argument("--seed", type=int, default=0, help="base seed of agents and oracle")
    run.add_argument("--houses", type=int, help="houses of the split (default: 61/15/14)")
    add_preset_option(run)
    run.add_argument("--max-steps", type=int, default=500, help="counted-step cap (default 500)")
    run.add_argument("--cache-dir", help="where built splits are kept (default ~/.cache/vlln)")
    run.add_argument("--stop-after", type=int, help="play at most N episodes now, then stop")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    model = run.add_argument_group("model agents (openai-vlm, vlln)")
    model.add_argument("--base-url", help="OpenAI-compatible server, e.g. http://localhost:8000/v1")
    model.add_argument("--model", help="openai-vlm: the served model's name; vlln: its folder")
    model.add_argument("--api-key-env", help="variable holding the key (default OPENAI_API_KEY)")
    model.add_argument(
        "--model-timeout", type=float, help="deadline of each whole request (default 60 s)"
    )
    model.add_argument("--model-retries", type=int, help="retries per request (default 4)")
    model.add_argument("--model-cache", help="folder caching model replies (default: none)")

    run.add_argument(
        "--no-sweep",
        action="store_true",
        help="play every budget on its own instead of sharing prefixes (same records, slower)",
    )
    add_ray_options(run, chunks=True)
    model.add_argument("--device", help="vlln: torch device (default cuda if present, else cpu)")
    model.add_argument("--max-tokens", type=int, help="longest model reply in tokens (default 128)")
    served = run.add_argument_group("the vlln agent's model server on each Ray node (docs/ray.md)")
    served.add_argument("--model-cpus", type=float, default=1.0, help="its CPUs (default 1)")
    served.add_argument(
        "--model-gpus",
        type=float,
        help="its GPUs (default 1 when the cluster has GPUs and --device is not cpu, else 0)",
    )
    served.add_argument(
        "--model-batch", type=int, default=8, help="most requests answered at once (default 8)"
    )
    run.set_defaults(handler=_eval)

    score = commands.add_parser("score", help="recompute every metric from run directories")
    score.add_argument("dirs", nargs="+", help="run directories (e.g. the shards of one run)")
    score.add_argument("--json", action="store_true", help="print the summary as JSON")
    report = commands.add_parser("report", help="report.md and report.html of run directories")
    report.add_argument("dirs", nargs="+", help="run directories, compared side by side")
    report.add_argument("--out", help="report directory (default DIR/report for one run)")
    report.add_argument("--samples", type=int, default=4, help="episode maps per run (default 4)")
    report.add_argument(
        "--videos", type=int, default=0, help="episode videos per run (MP4, needs vlln[video])"
    )
    report.add_argument("--scenes", help="folder of scanned scenes (default: the run's --scenes)")
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


def _video(args: argparse.Namespace) -> int:
    from vlln.eval.videos import make_video

    out = Path(args.out) if args.out else None
    scenes = Path(args.scenes) if args.scenes else None
    path, seconds = make_video(Path(args.source), out, args.episode, args.budget, scenes)
    print(f"wrote {path} ({seconds:.1f} s)")
    return 0


def add_video_command(commands: Commands) -> None:
    video = commands.add_parser("video", help="an MP4 of an episode: view, map, dialog captions")
    video.add_argument("source", help="a run directory, a results .jsonl or a record .json")
    video.add_argument("--episode", help="episode id (default: the one with the most dialog)")
    video.add_argument("--budget", type=int, help="dialog budget (default: the largest)")
    video.add_argument("--out", help="MP4 file (default SOURCE_DIR/videos/video_<id>_b<k>.mp4)")
    video.add_argument("--scenes", help="folder of scanned scenes (default: the run's --scenes)")
    video.set_defaults(handler=_video)


def add_demo_command(commands: Commands) -> None:
    demo = commands.add_parser("demo", help="the main job on the built-in houses")
    demo.add_argument("--out", default="out/demo", help="output directory (default out/demo)")
    demo.set_defaults(handler=_demo)
