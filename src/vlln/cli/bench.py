"""``vlln bench ...``: the speed and memory figures."""

from __future__ import annotations

import argparse
from pathlib import Path

from vlln.cli.options import Commands, add_preset_option


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
        subdivide=args.subdivide,
    )
    return 0


def _bench_eval(args: argparse.Namespace) -> int:
    from vlln.bench.eval import compare_presets

    cache_dir = None if args.cache_dir is None else Path(args.cache_dir)
    compare_presets(episodes=args.episodes, as_json=args.json, cache_dir=cache_dir)
    return 0


def _bench_oracle(args: argparse.Namespace) -> int:
    from vlln.extras import SERVICE_BENCH_PACKAGES, require_extra

    require_extra("serve", "vlln bench oracle (its service figures)", SERVICE_BENCH_PACKAGES)
    from vlln.bench.oracle import run_oracle_benchmark

    run_oracle_benchmark(
        seed=args.seed,
        questions=args.questions,
        as_json=args.json,
        service_scenes=args.service_scenes,
    )
    return 0


def _bench_storeys(args: argparse.Namespace) -> int:
    from vlln.bench.storeys import run_storeys_benchmark

    run_storeys_benchmark(
        houses=args.houses, floors=args.floors, per_house=args.per_house, as_json=args.json
    )
    return 0


def _bench_frontier_storeys(args: argparse.Namespace) -> int:
    from vlln.bench.frontier_storeys import run_frontier_storeys_benchmark

    run_frontier_storeys_benchmark(
        houses=args.houses, floors=args.floors, episodes=args.episodes, as_json=args.json
    )
    return 0


def _bench_agent(args: argparse.Namespace) -> int:
    from vlln.bench.agent import run_agent_benchmark
    from vlln.bench.agent_model import run_model_benchmark

    run_agent_benchmark(seed=args.seed, repeats=args.repeats, as_json=args.json)
    run_model_benchmark(seed=args.seed, as_json=args.json)
    return 0


def _bench_data(args: argparse.Namespace) -> int:
    from vlln.bench.data import run_data_benchmark

    run_data_benchmark(houses=args.houses, per_house=args.per_house, as_json=args.json)
    return 0


def _bench_fidelity(args: argparse.Namespace) -> int:
    from vlln.bench.fidelity import run_fidelity_benchmark

    run_fidelity_benchmark(
        Path(args.out),
        episodes=args.episodes,
        preset=args.preset,
        workers=args.workers,
        cache_dir=None if args.cache_dir is None else Path(args.cache_dir),
        as_json=args.json,
    )
    return 0


def _bench_web(args: argparse.Namespace) -> int:
    from vlln.bench.web import run_web_benchmark

    run_web_benchmark(presses=args.presses, browser=args.browser, as_json=args.json)
    return 0


def _bench_world(args: argparse.Namespace) -> int:
    from vlln.bench.world import run_world_benchmark

    run_world_benchmark(
        houses=args.houses,
        first_seed=args.first_seed,
        as_json=args.json,
        preset=args.preset,
        test_houses=args.test_houses,
    )
    return 0


def add_bench_commands(commands: Commands) -> None:
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
        "--subdivide",
        type=int,
        default=0,
        metavar="N",
        help="bench a scan: house --seed exported as Matterport3D with every triangle split "
        "into 4, N times (as `vlln world export --subdivide N`), then imported",
    )

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

    storeys = bench.add_parser(
        "storeys", help="the expert's success on targets on another storey (2- or 3-storey houses)"
    )
    storeys.add_argument("--houses", type=int, default=10, help="houses (default 10)")
    storeys.add_argument("--floors", type=int, default=2, help="storeys, 2 or 3 (default 2)")
    storeys.add_argument("--per-house", type=int, default=6, help="episodes per house (6)")
    storeys.add_argument("--json", action="store_true", help="print one JSON object per line")
    storeys.set_defaults(handler=_bench_storeys)
    frontier = bench.add_parser(
        "frontier-storeys", help="the frontier agent's IIGN success on houses of several storeys"
    )
    frontier.add_argument("--houses", type=int, default=2, help="test houses (default 2)")
    frontier.add_argument("--floors", type=int, default=2, help="storeys, 2 or 3 (default 2)")
    frontier.add_argument("--episodes", type=int, default=30, help="episodes (default 30)")
    frontier.add_argument("--json", action="store_true", help="print one JSON object per line")
    frontier.set_defaults(handler=_bench_frontier_storeys)
    bench_data = bench.add_parser("data", help="trajectories per hour of the data pipeline")
    bench_data.add_argument("--houses", type=int, default=2, help="training houses (default 2)")
    bench_data.add_argument(
        "--per-house", type=int, default=6, help="trajectories per house (default 6)"
    )
    bench_data.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_data.set_defaults(handler=_bench_data)
    fidelity = bench.add_parser(
        "fidelity",
        help="SR/SPL with 95%% intervals and the failure taxonomy of frontier (noisy detector) "
        "and expert on the paper's test protocol, beside the paper's Table 1",
    )
    fidelity.add_argument(
        "--episodes", type=int, default=200, help="episodes of test500 per run (default 200)"
    )
    fidelity.add_argument(
        "--out", default="out/fidelity", help="run folders, resumed (default out/fidelity)"
    )
    add_preset_option(fidelity)
    fidelity.add_argument("--workers", type=int, default=1, help="processes (default 1)")
    fidelity.add_argument("--cache-dir", help="where built splits are kept (default ~/.cache/vlln)")
    fidelity.add_argument("--json", action="store_true", help="print one JSON object per line")
    fidelity.set_defaults(handler=_bench_fidelity)
    bench_world = bench.add_parser(
        "world", help="catalogue size; objects, triangles and build time per house"
    )
    bench_world.add_argument("--houses", type=int, default=20, help="houses (default 20)")
    bench_world.add_argument("--first-seed", type=int, default=0, help="first seed (default 0)")
    add_preset_option(bench_world)
    bench_world.add_argument(
        "--test-houses",
        type=int,
        default=14,
        help="test houses whose statistics are printed beside the Matterport3D anchors "
        "(default 14, the whole test split; 0: none)",
    )
    bench_world.add_argument("--json", action="store_true", help="print one JSON object per line")
    bench_world.set_defaults(handler=_bench_world)
    web = bench.add_parser("web", help="key-press-to-new-frame latency in the browser")
    web.add_argument("--presses", type=int, default=200, help="key presses (default 200)")
    web.add_argument(
        "--browser", default="/usr/bin/chromium", help="Chromium executable (Debian: chromium)"
    )
    web.add_argument("--json", action="store_true", help="print one JSON object per line")
    web.set_defaults(handler=_bench_web)
