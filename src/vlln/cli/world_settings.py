"""The settings of ``vlln world show``, ``export``, ``import`` and ``catalogue``. Imported when
one of these commands is used."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal, Self

from pydantic import Field, model_validator
from pydantic_settings import CliPositionalArg

from vlln.config import Config
from vlln.world.options import GeneratorPresetOptions

Floors = Annotated[int | None, Field(ge=1, le=3)]


class HouseOptions(Config):
    """Which procedural house: its seed and the generator's parameters."""

    seed: int = 0
    """house seed"""
    param: tuple[str, ...] = ()
    """a house-generator parameter NAME=VALUE, e.g. --param max_rooms=6 (repeatable)"""
    floors: Floors = None
    """storeys joined by stairs, 1 to 3 (none: 1)"""

    @property
    def overrides(self) -> list[str]:
        """The generator parameters given, ``--floors`` among them."""
        return [*self.param, *([] if self.floors is None else [f"floors={self.floors}"])]


class ShowCommand(GeneratorPresetOptions, HouseOptions):
    """``vlln world show``: a top-down map and egocentric views of a house."""

    scene: Path | None = None
    """a scanned scene folder <dir>/<scene>/ instead of a seed"""
    out: Path
    """output directory"""
    views: Annotated[int, Field(ge=0)] = 4
    """number of rooms to view"""

    @model_validator(mode="after")
    def _one_kind_of_house(self) -> Self:
        if self.scene is not None and (self.param or self.floors is not None):
            raise ValueError("--scene shows a scanned scene as it is; drop --param and --floors")
        if self.preset is not None and (self.param or self.floors is not None):
            raise ValueError(
                f"--preset {self.preset} draws the house's parameters from the seed; drop "
                "--param and --floors, or drop --preset"
            )
        return self


class ExportCommand(HouseOptions):
    """``vlln world export``: a house as Matterport3D/HM3D scene folders."""

    out: Path
    """output folder (<out>/<style>/<scene>/)"""
    style: tuple[Literal["mp3d", "hm3d"], ...] = ()
    """mp3d or hm3d (repeatable; none: both)"""
    subdivide: Annotated[int, Field(ge=0)] = 0
    """split every triangle into 4, N times: a scan-sized test scene (N=2: 16x)"""
    episodes: bool = False
    """also write the house's episodes naming the scan (<style>/<scene>/<scene>.glb)"""


class ImportCommand(Config):
    """``vlln world import``: read a Matterport3D or HM3D scene folder."""

    scene: CliPositionalArg[Path]
    """scene folder <dir>/<scene>/ (.glb + .house or semantic)"""
    summary_out: Path | None = None
    """also write its scene summary under this folder"""


class CatalogueCommand(Config):
    """``vlln world catalogue``: every object category rendered, and a contact sheet."""

    out: Path
    """folder for <category>.png, catalogue.png"""
