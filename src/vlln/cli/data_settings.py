"""The settings of ``vlln data build``, ``balance``, ``export-sft``, ``episodes`` and
``stats``: what is stored with the data (:class:`BuildOptions`, :class:`BalanceConfig`,
:class:`SftConfig`) and how a command runs
(where it reads and writes, Ray, progress). Imported when one of these commands is used."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Self

from pydantic import Field, field_validator, model_validator
from pydantic_settings import CliPositionalArg

from vlln.cluster.options import RayOptions
from vlln.config import Config
from vlln.datagen.balance.select import BalanceConfig
from vlln.datagen.build import BuildOptions
from vlln.datagen.sft.config import SftConfig
from vlln.eval.sharding import Shard
from vlln.world.generator.presets import SMALL
from vlln.world.options import PresetOptions


class BuildCommand(RayOptions, BuildOptions):
    """``vlln data build``: a build's settings and how to run it."""

    out: Path
    """dataset folder (a rerun resumes it)"""
    shard: str | None = None
    """i/n: build every n-th house, starting at the i-th (none: every house)"""
    quiet: bool = False
    """no progress bars"""
    yes: bool = False
    """start a large build without asking (it states its cost)"""

    @field_validator("shard")
    @classmethod
    def _readable_shard(cls, value: str | None) -> str | None:
        if value is not None:
            Shard.parse(value)
        return value

    @model_validator(mode="after")
    def _shard_or_ray(self) -> Self:
        if self.shard is not None and self.ray is not None:
            raise ValueError("--shard and --ray do not mix: Ray shares the houses out itself")
        return self


class SftCommand(SftConfig):
    """``vlln data export-sft``: an export's settings and where it reads and writes."""

    dataset: CliPositionalArg[list[Path]]
    """one or more folders made by vlln data build (several: mixed for co-training)"""
    out: Path
    """output folder (sft.jsonl and images)"""
    quiet: bool = False
    """no progress bar"""


class BalanceCommand(BalanceConfig):
    """``vlln data balance``: a dataset cut down to even scene and category counts."""

    dataset: CliPositionalArg[Path]
    """a folder made by vlln data build"""
    out: Path
    """new folder for the balanced dataset and its report"""
    quiet: bool = False
    """no progress bar"""


class EpisodesCommand(PresetOptions):
    """``vlln data episodes``: the episode files of a split's procedural houses."""

    houses: Annotated[int, Field(ge=1)]
    """houses of the split"""
    out: Path
    """folder for <split>_<task>.json.gz"""
    split: str = "test"
    """house split"""
    seed: Annotated[int, Field(ge=0)] = 0
    """seed of every random choice"""
    floors: Annotated[int | None, Field(ge=1, le=3)] = None
    """small houses: storeys joined by stairs, 1 to 3 (none: 1)"""
    quiet: bool = False
    """no progress bar"""

    @model_validator(mode="after")
    def _floors_of_small_houses(self) -> Self:
        if self.floors is not None and self.preset != SMALL.name:
            raise ValueError(
                f"--floors sets the storeys of small houses; {self.preset} houses draw theirs "
                "from the seed: add --preset small, or drop --floors"
            )
        return self


class StatsCommand(Config):
    """``vlln data stats``: statistics, figure and report of a built dataset."""

    dataset: CliPositionalArg[Path]
    """a folder made by vlln data build"""
    out: Path | None = None
    """where to write them (none: DATASET/stats)"""
