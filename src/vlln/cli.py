"""Command-line entry points. Each command parses its arguments and calls one library function;
errors raised on purpose (vlln.errors.VllnError) are printed as one line, not a traceback."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from vlln.errors import ConfigError, VllnError
from vlln.web.command import add_bench_web, add_serve_commands

Handler = Callable[[argparse.Namespace], int]


def _world_show(args: argparse.Namespace) -> int:
    from vlln.viz.show import show_world
    from vlln.world.generator import parameters_from_overrides

    params = parameters_from_overrides(args.param)
    files = show_world(args.seed, Path(args.out), n_views=args.views, params=params)
    print(f"wrote {len(files)} images to {args.out} (map: {files[0]})")
    return 0


def _world_export(args: argparse.Namespace) -> int:
    from vlln.world.generator import generate_house, parameters_from_overrides
    from vlln.world.scans import export_scene

    house = generate_house(args.seed, parameters_from_overrides(args.param))
    for style in args.style or ["mp3d", "hm3d"]:
        print(f"wrote {export_scene(house, Path(args.out) / style, style)}")
    return 0


def _world_import(args: argparse.Namespace) -> int:
    import dataclasses
    import json

    from vlln.world.scans import import_scene
    from vlln.world.scene_summary import export_scene_summary

    house, report = import_scene(Path(args.scene))
    if args.summary_out:
        export_scene_summary(house, Path(args.summary_out))
    print(json.dumps(dataclasses.asdict(report), indent=2))
    return 0


def _bench_sim(args: argparse.Namespace) -> int:
    from vlln.bench.sim import run_sim_benchmark

    if args.envs is not None:
        from vlln.bench.parallel import run_parallel_benchmark

        run_parallel_benchmark(
            args.envs, seed=args.seed, frames=args.frames, repeats=args.repeats, as_json=args.json
        )
        return 0
    run_sim_benchmark(
        seed=args.seed,
        frames=args.frames,
        repeats=args.repeats,
        as_json=args.json,
        scene=None if args.scene is None else Path(args.scene),
    )
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
        agent_options=_agent_options(args),
        detector=args.detector,
    )
    from vlln.tasks.scenes import SceneCache

    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    if args.ray is not None:
        from vlln.cluster.evaluation import run_ray_evaluation

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
        )
    else:
        scenes = SceneCache(scenes_dir=args.scenes)
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
    print(
        f"{len(outcome.records)} of {outcome.planned} episodes in {args.out} ({state}); "
        f"played {outcome.played} in {outcome.seconds:.1f} s",
        file=sys.stderr,
    )
    print(outcome.health.line(), file=sys.stderr)
    if outcome.summary is not None:
        print((Path(args.out) / "summary.md").read_text(encoding="utf-8"), end="")
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
    )
    print(f"wrote {len(files)} files to {out}: {out / 'report.md'} and {out / 'report.html'}")
    return 0


def _bench_eval(args: argparse.Namespace) -> int:
    from vlln.bench.eval import run_eval_benchmark

    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    run_eval_benchmark(episodes=args.episodes, as_json=args.json, cache_dir=cache_dir)
    return 0


def _add_ray_options(parser: argparse.ArgumentParser, chunks: bool) -> None:
    """``--ray [ADDRESS]``, ``--retries`` and, for episodes, ``--chunk`` (docs/ray.md)."""
    parser.add_argument(
        "--ray",
        nargs="?",
        const="",
        metavar="ADDRESS",
        help="run on a Ray cluster (ADDRESS, 'auto', or none for RAY_ADDRESS or a local one)",
    )
    if chunks:
        parser.add_argument(
            "--chunk", type=int, default=4, help="episodes per Ray task (default 4)"
        )
    parser.add_argument(
        "--retries", type=int, default=3, help="re-runs of a task whose worker died (default 3)"
    )


def _add_eval_commands(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """`vlln eval`, `vlln score` and `vlln report`."""
    from vlln.tasks.metrics import ORACLE_SUCCESS_RADIUS, SUCCESS_RADIUS

    run = commands.add_parser("eval", help="play an agent over episodes into a run directory")
    run.add_argument("--agent", required=True, help="agent name (random, expert, frontier, ...)")
    run.add_argument("--task", required=True, help="iign, ign or objectnav")
    source = run.add_mutually_exclusive_group()
    source.add_argument("--split", default="test", help="built-in split (default test)")
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
    run.add_argument("--max-steps", type=int, default=500, help="counted-step cap (default 500)")
    run.add_argument("--cache-dir", help="where built splits are kept (default ~/.cache/vlln)")
    run.add_argument("--stop-after", type=int, help="play at most N episodes now, then stop")
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    model = run.add_argument_group("model agents (openai-vlm, vlln)")
    model.add_argument("--base-url", help="OpenAI-compatible server, e.g. http://localhost:8000/v1")
    model.add_argument("--model", help="openai-vlm: the served model's name; vlln: its folder")
    model.add_argument("--api-key-env", help="variable holding the key (default OPENAI_API_KEY)")
    model.add_argument("--model-timeout", type=float, help="seconds per request (default 60)")
    model.add_argument("--model-retries", type=int, help="retries per request (default 4)")
    model.add_argument("--model-cache", help="folder caching model replies (default: none)")

    run.add_argument(
        "--no-sweep",
        action="store_true",
        help="play every budget on its own instead of sharing prefixes (same records, slower)",
    )
    _add_ray_options(run, chunks=True)
    model.add_argument("--device", help="vlln: torch device (default cuda if present, else cpu)")
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


def _bench_agent(args: argparse.Namespace) -> int:
    from vlln.bench.agent import run_agent_benchmark
    from vlln.bench.agent_model import run_model_benchmark

    run_agent_benchmark(seed=args.seed, repeats=args.repeats, as_json=args.json)
    run_model_benchmark(seed=args.seed, as_json=args.json)
    return 0


def _video(args: argparse.Namespace) -> int:
    from vlln.eval.videos import make_video

    out = Path(args.out) if args.out else None
    path, seconds = make_video(Path(args.source), out, args.episode, args.budget)
    print(f"wrote {path} ({seconds:.1f} s)")
    return 0


def _add_video_command(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    video = commands.add_parser("video", help="an MP4 of an episode: view, map, dialog captions")
    video.add_argument("source", help="a run directory, a results .jsonl or a record .json")
    video.add_argument("--episode", help="episode id (default: the one with the most dialog)")
    video.add_argument("--budget", type=int, help="dialog budget (default: the largest)")
    video.add_argument("--out", help="MP4 file (default SOURCE_DIR/videos/video_<id>_b<k>.mp4)")
    video.set_defaults(handler=_video)


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
    from vlln.datagen.build import BuildConfig, build_dataset, summarize
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
    if args.ray is not None:
        from vlln.cluster.data import build_dataset_ray

        if shard is not None:
            raise ConfigError("--shard and --ray do not mix: Ray shares the houses out itself")
        out = build_dataset_ray(
            Path(args.out),
            config,
            address=args.ray or None,
            max_retries=args.retries,
            progress=not args.quiet,
        )
    else:
        out = build_dataset(Path(args.out), config, shard=shard, progress=not args.quiet)
    print(summarize(out).line())
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

    config = SftConfig(seed=args.seed, history_frames=args.history)
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
    _add_ray_options(build, chunks=False)
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
    sft.add_argument("--seed", type=int, default=0, help="seed of every random choice")
    sft.add_argument("--history", type=int, default=8, help="history frames (default 8)")
    sft.add_argument("--quiet", action="store_true", help="no progress bar")
    sft.set_defaults(handler=_data_export_sft)


def _train_sft(args: argparse.Namespace) -> int:
    from vlln.train.config import TrainConfig
    from vlln.train.sft import train_sft

    config = TrainConfig(
        data_dir=Path(args.data),
        model=args.model,
        out_dir=Path(args.out),
        epochs=args.epochs,
        learning_rate=args.lr,
        vision_learning_rate=args.vision_lr,
        batch_size=args.batch_size,
        grad_accumulation=args.grad_accum,
        max_steps=args.max_steps,
        save_steps=args.save_steps,
        logging_steps=args.logging_steps,
        workers=args.workers,
        seed=args.seed,
        lora=args.lora,
        lora_rank=args.lora_rank,
        max_pixels=args.max_pixels,
        gradient_checkpointing=args.gradient_checkpointing,
        resume=None if args.resume is None else Path(args.resume),
    )
    outcome = train_sft(config)
    resumed = f", resumed from {outcome.resumed_from}" if outcome.resumed_from else ""
    curve = " -> ".join(f"{loss:.3f}" for _, loss in outcome.losses) or "no new steps"
    print(
        f"trained to step {outcome.steps} on {outcome.samples} samples in "
        f"{outcome.seconds:.1f} s{resumed}; loss {curve}; model in {args.out}"
    )
    return 0


def _add_train_commands(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    train = commands.add_parser("train", help="fine-tuning").add_subparsers(
        dest="train_command", required=True
    )
    sft = train.add_parser("sft", help="supervised fine-tuning on a training export")
    sft.add_argument("--data", required=True, help="a folder made by vlln data export-sft")
    sft.add_argument("--model", required=True, help="model folder or Hugging Face name")
    sft.add_argument("--out", required=True, help="output folder (a rerun resumes it)")
    sft.add_argument("--epochs", type=float, default=5.0, help="epochs (default 5)")
    sft.add_argument("--lr", type=float, default=2e-5, help="learning rate (default 2e-5)")
    sft.add_argument(
        "--vision-lr", type=float, default=5e-6, help="vision tower's rate (default 5e-6)"
    )
    sft.add_argument("--batch-size", type=int, default=2, help="per device (default 2)")
    sft.add_argument("--grad-accum", type=int, default=1, help="accumulation steps (default 1)")
    sft.add_argument("--max-steps", type=int, default=-1, help="stop after N optimizer steps")
    sft.add_argument("--save-steps", type=int, default=500, help="checkpoint every N steps")
    sft.add_argument("--logging-steps", type=int, default=10, help="log loss every N steps")
    sft.add_argument("--workers", type=int, default=4, help="data-loader workers (default 4)")
    sft.add_argument("--seed", type=int, default=0, help="seed (default 0)")
    sft.add_argument("--lora", action="store_true", help="train LoRA adapters (small GPUs)")
    sft.add_argument("--lora-rank", type=int, default=16, help="LoRA rank (default 16)")
    sft.add_argument("--max-pixels", type=int, help="cap on pixels per image (fewer tokens)")
    sft.add_argument(
        "--gradient-checkpointing",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="recompute activations (default: on with a GPU)",
    )
    sft.add_argument("--resume", help="a checkpoint folder (default: the newest in --out)")
    sft.set_defaults(handler=_train_sft)


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
    export = world.add_parser("export", help="write a house as Matterport3D/HM3D scene folders")
    export.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    export.add_argument("--out", required=True, help="output folder (<out>/<style>/<scene>/)")
    export.add_argument("--style", action="append", choices=["mp3d", "hm3d"], help="repeatable")
    export.add_argument("--param", action="append", default=[], metavar="NAME=VALUE")
    export.set_defaults(handler=_world_export)
    imported = world.add_parser("import", help="read a Matterport3D or HM3D scene folder")
    imported.add_argument("scene", help="scene folder <dir>/<scene>/ (.glb + .house or semantic)")
    imported.add_argument("--summary-out", help="also write its scene summary under this folder")
    imported.set_defaults(handler=_world_import)

    bench = commands.add_parser("bench", help="speed and memory benchmarks").add_subparsers(
        dest="bench_command", required=True
    )
    sim = bench.add_parser("sim", help="renderer, motion and geodesic figures")
    sim.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    sim.add_argument("--frames", type=int, default=300, help="frames per timing (default 300)")
    sim.add_argument("--repeats", type=int, default=3, help="passes per frame rate (default 3)")
    sim.add_argument("--json", action="store_true", help="print one JSON object per line")
    sim.add_argument("--scene", help="a scanned scene folder instead of a procedural house")

    sim.add_argument(
        "--envs", type=int, help="steps/s of N environments in N processes against one (speed-up)"
    )
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
    bench_agent = bench.add_parser(
        "agent", help="a model agent's step cost outside the model; the local model's steps/s"
    )
    bench_agent.add_argument("--seed", type=int, default=0, help="house seed (default 0)")
    bench_agent.add_argument("--repeats", type=int, default=200, help="timed repeats (200)")
    bench_agent.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_agent.set_defaults(handler=_bench_agent)

    bench_data = bench.add_parser("data", help="trajectories per hour of the data pipeline")
    bench_data.add_argument("--houses", type=int, default=2, help="training houses (default 2)")
    bench_data.add_argument(
        "--per-house", type=int, default=6, help="trajectories per house (default 6)"
    )
    bench_data.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_data.set_defaults(handler=_bench_data)
    add_bench_web(bench)

    demo = commands.add_parser("demo", help="the main job on the built-in houses")
    demo.add_argument("--out", default="out/demo", help="output directory (default out/demo)")
    demo.set_defaults(handler=_demo)
    _add_eval_commands(commands)
    _add_oracle_commands(commands)
    _add_data_commands(commands)
    add_serve_commands(commands)
    _add_video_command(commands)
    _add_train_commands(commands)
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
