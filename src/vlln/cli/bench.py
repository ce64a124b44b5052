"""``vlln bench ...``: the speed and memory figures. Each command's flags come from its
settings class in :mod:`vlln.bench.settings`."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands

if TYPE_CHECKING:
    from vlln.bench.settings import (
        AgentBench,
        DataBench,
        EvalBench,
        FidelityBench,
        FrontierStoreysBench,
        OracleBench,
        SimBench,
        StoreysBench,
        WebBench,
        WorldBench,
    )


def _settings(name: str) -> Callable[[], type[Any]]:
    """The settings class ``name``, imported when its command is used."""

    def load() -> type[Any]:
        from vlln.bench import settings

        loaded: type[Any] = getattr(settings, name)
        return loaded

    return load


def _bench_sim(config: SimBench) -> int:
    from vlln.bench.sim import run_sim_benchmark

    if config.envs is not None:
        from vlln.bench.parallel import run_parallel_benchmark

        run_parallel_benchmark(
            config.envs,
            seed=config.seed,
            frames=config.frames,
            repeats=config.repeats,
            as_json=config.as_json,
        )
        return 0
    run_sim_benchmark(
        seed=config.seed,
        frames=config.frames,
        repeats=config.repeats,
        as_json=config.as_json,
        scene=config.scene,
        subdivide=config.subdivide,
    )
    return 0


def _bench_eval(config: EvalBench) -> int:
    from vlln.bench.eval import compare_presets

    compare_presets(episodes=config.episodes, as_json=config.as_json, cache_dir=config.cache_dir)
    return 0


def _bench_oracle(config: OracleBench) -> int:
    from vlln.extras import SERVICE_BENCH_PACKAGES, require_extra

    require_extra("serve", "vlln bench oracle (its service figures)", SERVICE_BENCH_PACKAGES)
    from vlln.bench.oracle import run_oracle_benchmark

    run_oracle_benchmark(
        seed=config.seed,
        questions=config.questions,
        as_json=config.as_json,
        service_scenes=config.service_scenes,
    )
    return 0


def _bench_storeys(config: StoreysBench) -> int:
    from vlln.bench.storeys import run_storeys_benchmark

    run_storeys_benchmark(
        houses=config.houses,
        floors=config.floors,
        per_house=config.per_house,
        as_json=config.as_json,
    )
    return 0


def _bench_frontier_storeys(config: FrontierStoreysBench) -> int:
    from vlln.bench.frontier_storeys import run_frontier_storeys_benchmark

    run_frontier_storeys_benchmark(
        houses=config.houses,
        floors=config.floors,
        episodes=config.episodes,
        as_json=config.as_json,
    )
    return 0


def _bench_agent(config: AgentBench) -> int:
    from vlln.bench.agent import run_agent_benchmark
    from vlln.bench.agent_model import run_model_benchmark

    run_agent_benchmark(seed=config.seed, repeats=config.repeats, as_json=config.as_json)
    run_model_benchmark(seed=config.seed, as_json=config.as_json)
    return 0


def _bench_data(config: DataBench) -> int:
    from vlln.bench.data import run_data_benchmark

    run_data_benchmark(houses=config.houses, per_house=config.per_house, as_json=config.as_json)
    return 0


def _bench_fidelity(config: FidelityBench) -> int:
    from vlln.bench.fidelity import run_fidelity_benchmark

    run_fidelity_benchmark(
        config.out,
        episodes=config.episodes,
        preset=config.preset,
        workers=config.workers,
        cache_dir=config.cache_dir,
        as_json=config.as_json,
    )
    return 0


def _bench_web(config: WebBench) -> int:
    from vlln.bench.web import run_web_benchmark

    run_web_benchmark(presses=config.presses, browser=config.browser, as_json=config.as_json)
    return 0


def _bench_world(config: WorldBench) -> int:
    from vlln.bench.world import run_world_benchmark

    run_world_benchmark(
        houses=config.houses,
        first_seed=config.first_seed,
        as_json=config.as_json,
        preset=config.preset,
        test_houses=config.test_houses,
    )
    return 0


def add_bench_commands(commands: Commands) -> None:
    bench = commands.add_parser("bench", help="speed and memory benchmarks").add_subparsers(
        dest="bench_command", required=True
    )
    add_config_command(
        bench,
        "sim",
        _settings("SimBench"),
        _bench_sim,
        help="renderer, motion and geodesic figures",
    )
    add_config_command(
        bench,
        "eval",
        _settings("EvalBench"),
        _bench_eval,
        help="episodes per hour of the evaluation runner",
    )
    add_config_command(
        bench,
        "oracle",
        _settings("OracleBench"),
        _bench_oracle,
        help="answer latency of the offline oracle",
    )
    add_config_command(
        bench,
        "agent",
        _settings("AgentBench"),
        _bench_agent,
        help="a model agent's step cost outside the model; the local model's steps/s",
    )
    add_config_command(
        bench,
        "storeys",
        _settings("StoreysBench"),
        _bench_storeys,
        help="the expert's success on targets on another storey (2- or 3-storey houses)",
    )
    add_config_command(
        bench,
        "frontier-storeys",
        _settings("FrontierStoreysBench"),
        _bench_frontier_storeys,
        help="the frontier agent's IIGN success on houses of several storeys",
    )
    add_config_command(
        bench,
        "data",
        _settings("DataBench"),
        _bench_data,
        help="trajectories per hour of the data pipeline",
    )
    add_config_command(
        bench,
        "fidelity",
        _settings("FidelityBench"),
        _bench_fidelity,
        help="SR/SPL with 95%% intervals and the failure taxonomy of frontier (noisy detector) "
        "and expert on the paper's test protocol, beside the paper's Table 1",
    )
    add_config_command(
        bench,
        "world",
        _settings("WorldBench"),
        _bench_world,
        help="catalogue size; objects, triangles and build time per house",
    )
    add_config_command(
        bench,
        "web",
        _settings("WebBench"),
        _bench_web,
        help="key-press-to-new-frame latency in the browser",
    )
