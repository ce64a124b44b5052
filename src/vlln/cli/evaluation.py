"""``vlln demo``, ``vlln eval``, ``vlln score``, ``vlln report`` and ``vlln video``."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING

from vlln.cli.eval_configs import (
    DemoCommand,
    EvalCommand,
    ReportCommand,
    ScoreCommand,
    VideoCommand,
)
from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands
from vlln.errors import ConfigError
from vlln.eval.config import EvalConfig

if TYPE_CHECKING:
    from vlln.eval.runner import RunOutcome


def _demo(config: DemoCommand) -> int:
    from vlln.demo import run_demo

    run_demo(config.out)
    return 0


def _eval(command: EvalCommand) -> int:
    from vlln.eval.run_dir import summary_md_file
    from vlln.eval.runner import run_evaluation

    config = command.run_settings()
    _warn_of_other_houses(config)
    if command.ray is not None:
        from vlln.cluster.evaluation import run_ray_evaluation
        from vlln.cluster.model_server import ServerStats
        from vlln.cluster.options import ServingOptions

        def report_servers(stats: list[ServerStats]) -> None:
            for server in stats:
                print(f"model server: {server.describe()}", file=sys.stderr)

        if config.scenes is not None:
            raise ConfigError("--scenes and --ray do not mix yet: evaluate scanned scenes locally")
        if command.concurrent > 1:
            raise ConfigError(
                "--concurrent and --ray do not mix: on Ray each node's model server batches "
                "the calls of its workers (--model-batch)"
            )
        outcome = run_ray_evaluation(
            config,
            command.out,
            address=command.ray_address,
            cache_dir=command.cache_dir,
            episodes_per_chunk=command.chunk,
            max_retries=command.retries,
            progress=not command.quiet,
            sweep=command.sweep,
            serving=ServingOptions.build(
                command.model_dump(include=set(ServingOptions.model_fields))
            ),
            on_model_stats=report_servers,
        )
    else:
        from vlln.tasks.scenes import SceneCache

        scenes = SceneCache(scenes_dir=config.scenes)
        try:
            outcome = run_evaluation(
                config,
                command.out,
                cache_dir=command.cache_dir,
                stop_after=command.stop_after,
                progress=not command.quiet,
                scenes=scenes,
                sweep=command.sweep,
                concurrent=command.concurrent,
                on_model_stats=lambda model: print(f"model: {model.describe()}", file=sys.stderr),
            )
        finally:
            scenes.close()
    out = command.out
    state = "complete" if outcome.complete else "incomplete: rerun the same command to go on"
    for line in outcome.repaired:
        print(f"repaired: {line.describe()}", file=sys.stderr)
    refused = f", {outcome.health.refused} refused" if outcome.health.refused else ""
    print(
        f"{len(outcome.records)} of {outcome.planned} episodes in {out}{refused} "
        f"({state}); played {outcome.played} in {outcome.seconds:.1f} s",
        file=sys.stderr,
    )
    print(outcome.health.line(), file=sys.stderr)
    if outcome.summary is not None:
        print(summary_md_file(out).read_text(encoding="utf-8"), end="")
    problem = _unmeasured(outcome)
    if problem:
        print(
            f"error: {problem}; the episodes in {out} measure the servers, not the agent: fix "
            "them and rerun with a new --out",
            file=sys.stderr,
        )
        return 1
    return 0


def _unmeasured(outcome: RunOutcome) -> str:
    """Why the run measured the servers, not the agent ("" when it did not,
    :attr:`RunHealth.servers_silent`), with the first server error quoted. Replies that all
    were unreadable are the model's own answers (an untrained model gives them): the health
    line says so, and the run is its result."""
    problem = outcome.health.servers_silent
    errors = [c.error for r in outcome.records for c in r.model_calls if c.text is None]
    if problem and errors and not outcome.health.oracle_silent:
        problem += f" (the first: {' '.join(str(errors[0]).split())[:200]})"
    return problem


def _warn_of_other_houses(config: EvalConfig) -> None:
    """A fine-tuned model scored on another preset's houses than it was trained on is
    measured out of its training distribution: say so before the run."""
    from vlln.agents.local.options import VllnOptions

    options = config.agent_options
    if not isinstance(options, VllnOptions) or config.split is None:
        return
    from vlln.agents.local.card import read_card

    trained = read_card(options.model_dir).houses
    if trained is not None and trained != config.preset:
        print(
            f"warning: {options.model} was trained on {trained} houses and this run scores it "
            f"on {config.preset} houses (--preset {trained} scores it on its own kind)",
            file=sys.stderr,
        )


def _score(config: ScoreCommand) -> int:
    import json

    from vlln.eval.health import run_health
    from vlln.eval.results import load_runs
    from vlln.eval.summary import summarize_run, summary_json, summary_markdown

    contents = load_runs(config.dirs)
    health = run_health(contents)
    print(health.line(), file=sys.stderr)
    groups = summarize_run(contents.records, config.success_radius, config.os_radius)
    if config.as_json:
        data = summary_json(groups) | {"health": health.to_json()}
        print(json.dumps(data, indent=2, allow_nan=False))
    else:
        markdown = summary_markdown(groups, "Scores of " + ", ".join(map(str, config.dirs)))
        print(markdown + f"\n{health.line()}\n", end="")
    if health.servers_silent:
        print(f"error: {health.servers_silent}: these runs measure the servers", file=sys.stderr)
        return 1
    return 0


def _report(config: ReportCommand) -> int:
    from vlln.eval.report import write_report

    dirs = config.dirs
    out = config.out or (dirs[0] / "report" if len(dirs) == 1 else Path("report"))
    files = write_report(dirs, out, config)
    print(f"wrote {len(files)} files to {out}: {out / 'report.md'} and {out / 'report.html'}")
    return 0


def add_eval_commands(commands: Commands) -> None:
    """`vlln eval`, `vlln score` and `vlln report`."""
    add_config_command(
        commands,
        "eval",
        EvalCommand,
        _eval,
        help="play an agent over episodes into a run directory",
        replay=True,
    )
    add_config_command(
        commands, "score", ScoreCommand, _score, help="recompute every metric from run directories"
    )
    add_config_command(
        commands,
        "report",
        ReportCommand,
        _report,
        help="report.md and report.html of run directories",
    )


def _video(config: VideoCommand) -> int:
    from vlln.eval.videos import make_video

    path, seconds = make_video(
        config.source, config.out, config.episode, config.budget, config.scenes
    )
    print(f"wrote {path} ({seconds:.1f} s)")
    return 0


def add_video_command(commands: Commands) -> None:
    add_config_command(
        commands,
        "video",
        VideoCommand,
        _video,
        help="an MP4 of an episode: view, map, dialog captions",
    )


def add_demo_command(commands: Commands) -> None:
    add_config_command(
        commands, "demo", DemoCommand, _demo, help="the main job on the built-in houses"
    )
