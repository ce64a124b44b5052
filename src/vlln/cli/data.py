"""``vlln data ...``: build, summarise and export training data."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands

if TYPE_CHECKING:
    from vlln.cli.data_settings import (
        BalanceCommand,
        BuildCommand,
        EpisodesCommand,
        SftCommand,
        StatsCommand,
    )


def _build_command() -> type[BuildCommand]:
    from vlln.cli.data_settings import BuildCommand

    return BuildCommand


def _episodes_command() -> type[EpisodesCommand]:
    from vlln.cli.data_settings import EpisodesCommand

    return EpisodesCommand


def _stats_command() -> type[StatsCommand]:
    from vlln.cli.data_settings import StatsCommand

    return StatsCommand


def _balance_command() -> type[BalanceCommand]:
    from vlln.cli.data_settings import BalanceCommand

    return BalanceCommand


def _sft_command() -> type[SftCommand]:
    from vlln.cli.data_settings import SftCommand

    return SftCommand


def _data_build(command: BuildCommand) -> int:
    from vlln.datagen.build import BuildConfig, BuildOptions, build_dataset, summarize
    from vlln.datagen.cost import build_cost
    from vlln.eval.sharding import Shard
    from vlln.files import check_output_folder

    config = BuildConfig(**command.model_dump(include=set(BuildOptions.model_fields)))
    check_output_folder(command.out)
    shard = Shard.parse(command.shard) if command.shard else None
    houses = -(-config.houses // shard.count) if shard else config.houses
    cost = build_cost(houses, config.per_house)
    print(cost.line(), file=sys.stderr)
    if cost.large and not command.yes and sys.stdin.isatty():
        answer = input("this is a large build; start it? [y/N] ")
        if answer.strip().lower() not in ("y", "yes"):
            print("not started (pass --yes to skip this question)", file=sys.stderr)
            return 1
    if command.ray is not None:
        from vlln.cluster.data import build_dataset_ray

        out = build_dataset_ray(
            command.out,
            config,
            address=command.ray_address,
            max_retries=command.retries,
            progress=not command.quiet,
        )
    else:
        out = build_dataset(command.out, config, shard=shard, progress=not command.quiet)
    print(summarize(out).line())
    print(f"dataset in {out} (summarise it with: vlln data stats {out})")
    return 0


def _data_stats(command: StatsCommand) -> int:
    from vlln.datagen.stats.report import write_stats

    paths = write_stats(command.dataset, command.out)
    print("wrote " + ", ".join(str(path) for path in paths))
    return 0


def _data_balance(command: BalanceCommand) -> int:
    from vlln.datagen.balance import BalanceConfig, balance_dataset
    from vlln.files import check_output_folder

    check_output_folder(command.out)
    config = BalanceConfig(**command.model_dump(include=set(BalanceConfig.model_fields)))
    result = balance_dataset(command.dataset, command.out, config, progress=not command.quiet)
    selection = result.selection
    print(
        f"kept {len(selection.kept)} of {sum(selection.scenes_before.values())} trajectories "
        f"(at most {selection.per_scene} per scene, {selection.per_category} per category)"
    )
    print(f"balanced dataset in {result.out}; report: {result.report[0]}")
    return 0


def _data_export_sft(command: SftCommand) -> int:
    from vlln.datagen.sft.config import SftConfig
    from vlln.datagen.sft.export import export_sft
    from vlln.datagen.sft.records import SFT_FILE

    config = SftConfig(**command.model_dump(include=set(SftConfig.model_fields)))
    summary = export_sft(command.dataset, command.out, config, progress=not command.quiet)
    negatives = summary.by_kind.get("negative")
    print(
        f"wrote {summary.samples} conversations from {summary.trajectories} trajectories "
        f"({summary.images} images) to {command.out / SFT_FILE}"
        + ("" if negatives is None else f"; {negatives} of them hard negatives")
    )
    return 0


def _data_episodes(command: EpisodesCommand) -> int:
    from vlln.tasks.split_files import build_split

    out = build_split(
        command.split,
        command.houses,
        command.out,
        command.seed,
        floors=command.floors or 1,
        progress=not command.quiet,
        preset=command.preset,
    )
    ign = out / f"{command.split}_ign.json.gz"
    print(f"episodes in {out} (evaluate with: vlln eval --episode-file {ign})")
    return 0


def add_data_commands(commands: Commands) -> None:
    data = commands.add_parser("data", help="the training-data pipeline").add_subparsers(
        dest="data_command", required=True
    )
    add_config_command(
        data,
        "build",
        _build_command,
        _data_build,
        help="scene summaries, episodes and dialog-augmented trajectories",
    )
    add_config_command(
        data,
        "episodes",
        _episodes_command,
        _data_episodes,
        help="episode files (IIGN, IGN, ObjectNav) of a split's procedural houses",
    )
    add_config_command(
        data,
        "stats",
        _stats_command,
        _data_stats,
        help="statistics, figure and report of a built dataset",
    )
    add_config_command(
        data,
        "balance",
        _balance_command,
        _data_balance,
        help="a dataset cut down to even scene and target-category counts, with a report",
    )
    add_config_command(
        data,
        "export-sft",
        _sft_command,
        _data_export_sft,
        help="trajectories as multi-image conversations for fine-tuning",
    )
