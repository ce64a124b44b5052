from __future__ import annotations

import json
import math
from typing import Any

import pytest

from vlln.errors import ConfigError
from vlln.tasks.metrics import (
    msp,
    navigation_error,
    oracle_success,
    record_spl,
    spl,
    success,
)
from vlln.tasks.record import DialogTurn, EndReason, EpisodeRecord

INF = math.inf


def make_record(**overrides: Any) -> EpisodeRecord:
    """A successful IIGN episode (start 4 m away, travelled 5 m, stopped 0.1 m from the goal);
    one counted step per distance of the trace unless ``steps`` is given."""
    values: dict[str, Any] = {
        "episode_id": "0",
        "scene_id": "house_0",
        "task": "iign",
        "agent": "test",
        "budget": 0,
        "object_category": "chair",
        "target_ids": [7],
        "end_reason": EndReason.STOP.value,
        "geodesic_start": 4.0,
        "geodesic_trace": [3.0, 2.0, 1.0, 0.1],
        "path_length": 5.0,
        "stop_instance_id": 7,
        "stop_instance_category": "chair",
        "target_seen_step": 2,
    }
    values.update(overrides)
    values.setdefault("steps", len(values["geodesic_trace"]))
    return EpisodeRecord(**values)


def ask(step: int, answered: bool = True) -> DialogTurn:
    return DialogTurn(step, "where is it?", "left", "route", answered)


def test_success_needs_stop_and_strictly_inside_radius() -> None:
    assert success(make_record())
    assert not success(make_record(geodesic_trace=[1.0, 0.25]))  # exactly 0.25 m
    assert success(make_record(geodesic_trace=[1.0, 0.2499]))
    assert not success(make_record(end_reason=EndReason.STEP_CAP.value))  # at goal, no STOP
    assert success(make_record(geodesic_trace=[1.0, 0.4]), success_radius=0.5)


def test_success_without_steps_uses_start_distance() -> None:
    assert success(make_record(geodesic_start=0.1, geodesic_trace=[], path_length=0.0))
    assert not success(make_record(geodesic_start=2.0, geodesic_trace=[], path_length=0.0))


def test_success_rejects_bad_radius() -> None:
    with pytest.raises(ConfigError, match="success_radius"):
        success(make_record(), success_radius=0.0)
    with pytest.raises(ConfigError, match="success_radius"):
        success(make_record(), success_radius=math.nan)


def test_spl_formula() -> None:
    assert spl(True, 4.0, 5.0) == pytest.approx(0.8)
    assert spl(True, 4.0, 4.0) == pytest.approx(1.0)
    assert spl(False, 4.0, 4.0) == 0.0
    assert spl(True, 0.0, 0.0) == 1.0  # already at the goal
    assert spl(True, 0.0, 3.0) == 1.0
    assert spl(False, 0.0, 0.0) == 0.0
    assert spl(True, 4.0, 3.0) == 1.0  # L < d0 is impossible; clamp, never above 1
    assert spl(True, INF, 3.0) == 0.0
    assert spl(True, 2.0, INF) == 0.0


def test_spl_rejects_negative_or_nan_lengths() -> None:
    with pytest.raises(ConfigError, match="shortest"):
        spl(True, -1.0, 2.0)
    with pytest.raises(ConfigError, match="travelled"):
        spl(True, 1.0, math.nan)


def test_record_spl() -> None:
    assert record_spl(make_record()) == pytest.approx(0.8)
    assert record_spl(make_record(geodesic_trace=[1.0, 0.25])) == 0.0
    assert record_spl(make_record(path_length=10.0)) == pytest.approx(0.4)


def test_oracle_success_depends_on_radius() -> None:
    passed_by = make_record(
        end_reason=EndReason.STEP_CAP.value, geodesic_trace=[5.0, 2.0, 1.0, 2.5, 6.0]
    )
    assert oracle_success(passed_by)  # default 3.0 m
    assert not oracle_success(passed_by, radius=0.25)
    assert oracle_success(passed_by, radius=1.5)
    assert not oracle_success(passed_by, radius=1.0)  # strictly closer than the radius


def test_oracle_success_counts_start() -> None:
    record = make_record(geodesic_start=0.5, geodesic_trace=[4.0, 8.0])
    assert oracle_success(record)
    assert not oracle_success(make_record(geodesic_start=INF, geodesic_trace=[INF, 5.0]))


def test_navigation_error_is_final_distance() -> None:
    assert navigation_error(make_record()) == pytest.approx(0.1)
    assert navigation_error(make_record(geodesic_trace=[2.0, INF])) == INF
    assert navigation_error(make_record(geodesic_start=3.5, geodesic_trace=[])) == 3.5


def test_msp_paper_example() -> None:
    value = msp([19.6, 22.0, 23.0, 23.0, 25.2, 25.4])
    assert round(value, 2) == 4.12
    assert value == pytest.approx(4.12, abs=1e-9)


def test_msp_small_cases() -> None:
    assert msp([10.0, 15.0]) == pytest.approx(5.0)
    assert msp([10.0, 8.0, 12.0]) == pytest.approx(0.0)
    assert msp((30.0, 20.0)) == pytest.approx(-10.0)


@pytest.mark.parametrize("rates", [[], [19.6]])
def test_msp_needs_two_rates(rates: list[float]) -> None:
    with pytest.raises(ConfigError, match="at least 2"):
        msp(rates)


def test_record_round_trip_keeps_metrics() -> None:
    record = make_record(
        geodesic_start=INF,
        geodesic_trace=[INF, 2.0, 0.2],
        budget=1,
        dialog=[ask(1), ask(3, False)],
    )
    restored = EpisodeRecord.from_json(record.to_json())
    assert success(restored) == success(record)
    assert oracle_success(restored) == oracle_success(record)
    assert navigation_error(restored) == pytest.approx(navigation_error(record))
    assert record_spl(restored) == record_spl(record) == 0.0


def test_a_stop_just_inside_the_radius_survives_the_json_round_trip() -> None:
    record = make_record(geodesic_trace=[1.0, 0.24999999])
    restored = EpisodeRecord.from_json(json.loads(json.dumps(record.to_json())))
    assert success(restored)
