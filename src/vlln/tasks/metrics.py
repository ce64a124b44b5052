"""Per-episode navigation metrics as plain functions over finished :class:`EpisodeRecord` s.

Every metric is recomputed from a record alone, so a results file can be re-scored with other
radii long after the run. Distances are geodesic metres to the *nearest goal view point* (the
navigable points inside a goal's box grown by 0.6 m); ``inf`` means unreachable.

* **Success** ``S = [stopped] * [d_T < r_s]``, ``d_T`` the final geodesic distance, success
  radius ``r_s = 0.25`` m, strictly less than.
* **SPL** ``S * d0 / max(d0, L)``, ``d0`` the geodesic start distance, ``L`` the travelled
  path length (sum of straight-line displacements).
* **Oracle success** ``[min(d0, d_1, ..., d_T) < r_o]``: ever within the oracle radius
  ``r_o`` of a view point. The reference hard-codes ``r_o = 3.0`` m; that default keeps our
  numbers comparable, and it is why OS sits far above SR.
* **Navigation error** ``d_T`` (``inf`` when the final position cannot reach any view point;
  aggregates count those instead of averaging them).
* **MSP** (mean success progress) over dialog budgets ``0..n`` with success rates
  ``s_0..s_n``: ``(1/n) * sum_{i=1..n} (s_i - s_0)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from vlln.errors import ConfigError
from vlln.tasks.record import EpisodeRecord

SUCCESS_RADIUS = 0.25
"""Metres; STOP closer than this to a goal view point is a success."""

ORACLE_SUCCESS_RADIUS = 3.0
"""Metres; the reference evaluator's hard-coded oracle-success radius."""


def require_radius(name: str, value: float) -> float:
    """Return ``value`` if it is a usable radius (finite, > 0), else raise ConfigError."""
    if not (math.isfinite(value) and value > 0.0):
        raise ConfigError(f"{name} must be a finite positive number of metres, got {value!r}")
    return value


def success(record: EpisodeRecord, success_radius: float = SUCCESS_RADIUS) -> bool:
    """True when the agent chose STOP strictly closer than ``success_radius`` to a view point."""
    require_radius("success_radius", success_radius)
    return record.stopped and record.geodesic_final < success_radius


def spl(success: bool, shortest: float, travelled: float) -> float:
    """Success weighted by path length: ``S * d0 / max(d0, L)``.

    ``d0 = 0`` with success is 1.0 (nothing to travel); ``L < d0`` cannot happen on a real
    path but is clamped so a successful episode never scores above 1; an unreachable start
    (``d0 = inf``) scores 0.
    """
    if math.isnan(shortest) or shortest < 0.0:
        raise ConfigError(f"shortest path length must be >= 0 metres, got {shortest!r}")
    if math.isnan(travelled) or travelled < 0.0:
        raise ConfigError(f"travelled path length must be >= 0 metres, got {travelled!r}")
    if not success or math.isinf(shortest):
        return 0.0
    if shortest == 0.0:
        return 1.0
    return shortest / max(shortest, travelled)


def record_spl(record: EpisodeRecord, success_radius: float = SUCCESS_RADIUS) -> float:
    """SPL of one episode record (see :func:`spl`)."""
    return spl(success(record, success_radius), record.geodesic_start, record.path_length)


def oracle_success(record: EpisodeRecord, radius: float = ORACLE_SUCCESS_RADIUS) -> bool:
    """True when the agent was ever strictly closer than ``radius`` to a view point.

    The minimum runs over the start position and the position after every counted step,
    whether or not the agent stopped.
    """
    require_radius("oracle-success radius", radius)
    return min([record.geodesic_start, *record.geodesic_trace]) < radius


def navigation_error(record: EpisodeRecord) -> float:
    """Final geodesic distance to the nearest view point, metres (``inf`` when unreachable)."""
    return record.geodesic_final


def msp(success_rates: Sequence[float]) -> float:
    """Mean success progress: ``(1/n) * sum_{i=1..n} (s_i - s_0)`` for budgets ``0..n``.

    ``success_rates[i]`` is the success rate with a budget of ``i`` answered questions; the
    result is in the same unit (percentage points when the rates are percentages).
    """
    if len(success_rates) < 2:
        raise ConfigError(
            "MSP needs success rates for dialog budgets 0..n with n >= 1 "
            f"(at least 2 values), got {len(success_rates)}"
        )
    baseline = success_rates[0]
    gains = [rate - baseline for rate in success_rates[1:]]
    return sum(gains) / len(gains)
