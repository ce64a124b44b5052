"""Settings of the oracle service, checked once when the service is built."""

from __future__ import annotations

import math
from dataclasses import dataclass

from vlln.errors import ConfigError
from vlln.sim.simulator import SimulatorConfig
from vlln.tasks.episode import Episode

DEFAULT_MAX_BODY_BYTES = 64 * 1024


@dataclass(frozen=True)
class ServiceConfig:
    """What one oracle service serves and its limits.

    ``token``: when set, every request except ``GET /v1/health`` needs
    ``Authorization: Bearer <token>``. ``episodes``: the episodes sessions may name by
    ``episode_id``. ``max_sessions`` bounds the session store (least recently used dropped
    first); ``scene_capacity`` is how many simulators are kept, shared by all sessions of a
    scene. ``oracle_seed`` seeds every session's :class:`RuleOracle`, so answers are
    reproducible. ``floor_tolerance`` is how far (m) a pose's y may be from the floor.
    ``builds_per_minute`` and ``client_builds_per_minute`` bound the houses built for all
    clients together and for one client address (:mod:`vlln.oracle_service.limits`).
    """

    token: str | None = None
    episodes: tuple[Episode, ...] = ()
    max_sessions: int = 64
    scene_capacity: int = 2
    oracle_seed: int = 0
    max_body_bytes: int = DEFAULT_MAX_BODY_BYTES
    floor_tolerance: float = 0.3
    simulator: SimulatorConfig | None = None
    builds_per_minute: int = 60
    client_builds_per_minute: int = 20

    def __post_init__(self) -> None:
        if self.token is not None and (not self.token or self.token != self.token.strip()):
            raise ConfigError(
                "token must be a non-empty string without surrounding whitespace; leave it "
                "unset to serve without authentication (loopback only is advised)"
            )
        for name in (
            "max_sessions",
            "scene_capacity",
            "max_body_bytes",
            "builds_per_minute",
            "client_builds_per_minute",
        ):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ConfigError(f"{name} must be a whole number >= 1, got {value!r}")
        seed = self.oracle_seed
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise ConfigError(f"oracle_seed must be a whole number >= 0, got {seed!r}")
        if not (math.isfinite(self.floor_tolerance) and self.floor_tolerance >= 0.0):
            raise ConfigError(f"floor_tolerance must be >= 0 metres, got {self.floor_tolerance}")
        seen: set[str] = set()
        for episode in self.episodes:
            if episode.episode_id in seen:
                raise ConfigError(
                    f"episode_id {episode.episode_id!r} occurs twice among the served "
                    "episodes; sessions name episodes by id, so ids must be unique"
                )
            seen.add(episode.episode_id)
