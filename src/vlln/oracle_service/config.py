"""Settings of the oracle service, checked once when the service is built."""

from __future__ import annotations

import math
from typing import Annotated, Self

from pydantic import Field, SkipValidation, field_validator, model_validator

from vlln.config import Config
from vlln.sim.simulator import SimulatorConfig
from vlln.tasks.episode import Episode

DEFAULT_MAX_BODY_BYTES = 64 * 1024
DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765
DEFAULT_TOKEN_ENV = "VLLN_ORACLE_TOKEN"


class ServiceLimits(Config):
    """The service's limits and its oracle's seed (``vlln oracle serve`` takes them as flags)."""

    max_sessions: Annotated[int, Field(ge=1)] = 64
    """sessions kept (the least recently used dropped first)"""
    scene_capacity: Annotated[int, Field(ge=1)] = 2
    """simulators kept, shared by all sessions of a house"""
    oracle_seed: Annotated[int, Field(ge=0)] = 0
    """seed of every session's oracle (its paraphrases), so answers are reproducible"""
    max_body_bytes: Annotated[int, Field(ge=1)] = DEFAULT_MAX_BODY_BYTES
    """largest request body accepted"""
    floor_tolerance: float = 0.3
    """how far (m) a pose's y may be from the floor"""
    builds_per_minute: Annotated[int, Field(ge=1)] = 60
    """house builds, all clients together (vlln.oracle_service.limits)"""
    client_builds_per_minute: Annotated[int, Field(ge=1)] = 20
    """house builds one client address may cause"""

    @field_validator("floor_tolerance")
    @classmethod
    def _metres(cls, value: float) -> float:
        if not (math.isfinite(value) and value >= 0.0):
            raise ValueError(f"must be >= 0 metres, got {value}")
        return value


class ServiceConfig(ServiceLimits):
    """What one oracle service serves and its limits.

    ``token``: when set, every request except ``GET /v1/health`` needs
    ``Authorization: Bearer <token>``. ``episodes``: the episodes sessions may name by
    ``episode_id``. ``simulator``: the simulators' settings (none: the defaults).
    """

    token: str | None = None
    episodes: SkipValidation[tuple[Episode, ...]] = ()
    simulator: SkipValidation[SimulatorConfig | None] = None

    @field_validator("token")
    @classmethod
    def _bearer_token(cls, value: str | None) -> str | None:
        if value is not None and (not value or value != value.strip()):
            raise ValueError(
                "must be a non-empty string without surrounding whitespace; leave it unset "
                "to serve without authentication (loopback only is advised)"
            )
        return value

    @model_validator(mode="after")
    def _unique_episode_ids(self) -> Self:
        seen: set[str] = set()
        for episode in self.episodes:
            if episode.episode_id in seen:
                raise ValueError(
                    f"episode_id {episode.episode_id!r} occurs twice among the served "
                    "episodes; sessions name episodes by id, so ids must be unique"
                )
            seen.add(episode.episode_id)
        return self
