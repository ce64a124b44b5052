"""Settings of the run reports as config classes: ``vlln score`` and ``vlln report`` inherit
them, and :func:`vlln.eval.report.write_report` takes them, so their defaults live here once."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

from pydantic import Field

from vlln.config import Config
from vlln.tasks.metrics import ORACLE_SUCCESS_RADIUS, SUCCESS_RADIUS


class Radii(Config):
    """The radii that decide success, shared by ``vlln score`` and ``vlln report``."""

    success_radius: Annotated[float, Field(gt=0)] = SUCCESS_RADIUS
    """success radius in m (the reference's)"""
    os_radius: Annotated[float, Field(gt=0)] = ORACLE_SUCCESS_RADIUS
    """oracle-success radius in m (the reference's)"""


class ReportOptions(Radii):
    """What a report shows beside the metrics, and where scanned scenes are read from."""

    samples: Annotated[int, Field(ge=0)] = 4
    """episode maps per run"""
    videos: Annotated[int, Field(ge=0)] = 0
    """episode videos per run (MP4, needs vlln[video])"""
    scenes: Path | None = None
    """folder of scanned scenes (none: the run's --scenes)"""
