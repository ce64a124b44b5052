"""The settings of ``vlln oracle serve`` (the service's limits and where and how it listens)
and of ``vlln oracle classify-report`` and ``train-classifier``. Imported when one of these
commands is used."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

from pydantic import AliasChoices, Field

from vlln.config import Config
from vlln.oracle_service.config import DEFAULT_HOST, DEFAULT_PORT, ServiceLimits


class ServeCommand(ServiceLimits):
    """``vlln oracle serve``: the service's limits and where and how it listens."""

    host: str = DEFAULT_HOST
    """address to listen on (loopback only unless --allow-remote)"""
    port: Annotated[int, Field(ge=0, le=65535)] = DEFAULT_PORT
    """port (0: a free one)"""
    token_env: str | None = None
    """environment variable holding the bearer token; it must be set and not empty (none:
    VLLN_ORACLE_TOKEN when set, else no token, loopback only)"""
    episodes: Path | None = None
    """an episode file whose episodes sessions can name"""
    allow_remote: bool = False
    """allow a host other than loopback"""
    log_level: str = "warning"
    """uvicorn log level: critical, error, warning (no line per request), info or debug"""


class ClassifyReportCommand(Config):
    """``vlln oracle classify-report``: accuracy and confusion matrix of the offline classifier."""

    questions: Path | None = None
    """a JSON Lines question set (none: the held-out set of the repository's oracle_training/)"""
    as_json: Annotated[bool, Field(validation_alias=AliasChoices("json", "as_json"))] = False
    """print the figures as JSON"""


class TrainClassifierCommand(Config):
    """``vlln oracle train-classifier``: fit the offline question classifier."""

    seed: int = 0
    """seed of the typo copies"""
    out: Path | None = None
    """where to write it (none: the packaged artefact)"""


class ClassifyCvCommand(Config):
    """``vlln oracle classify-cv``: accuracy on questions the classifier was not trained on,
    without a held-out file: cross-validation over question families, and one set left out."""

    folds: Annotated[int, Field(ge=2)] = 5
    """cross-validation folds"""
    seed: int = 0
    """seed of the typo copies"""
    leave_out: str = "v6"
    """training set to test on, trained on the others"""
    as_json: Annotated[bool, Field(validation_alias=AliasChoices("json", "as_json"))] = False
    """print the figures (and misses) as JSON"""
