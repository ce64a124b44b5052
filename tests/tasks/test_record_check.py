"""Episode records read from JSON: every field checked for type and range, the field named."""

from __future__ import annotations

import json
import math
from typing import Any

import pytest

from tests.tasks.test_metrics import ask, make_record
from vlln.errors import DataFormatError
from vlln.tasks.record import EpisodeRecord


def valid() -> dict[str, Any]:
    return make_record(
        budget=1, dialog=[ask(3)], positions=[[0.0, 1.0, 0.5]], actions=["forward"]
    ).to_json()


def test_valid_record_round_trips() -> None:
    data = valid()
    assert EpisodeRecord.from_json(json.loads(json.dumps(data))).to_json() == data


def test_a_model_agents_failures_and_calls_round_trip() -> None:
    data = valid() | {"failures": {"parse": 2, "server": 1}, "failed_actions": 3}
    data["detector"] = "noisy"
    data["model_calls"] = [
        {
            "step": 0,
            "text": None,
            "error": "HTTP 503",
            "look_down": False,
            "latency_ms": 12.5,
            "prompt_tokens": 0,
            "completion_tokens": 0,
        }
    ]
    assert EpisodeRecord.from_json(json.loads(json.dumps(data))).to_json() == data


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("steps", "lots", r"field 'steps'.*integer.*'lots'"),
        ("budget", -3, r"field 'budget'.*>= 0.*-3"),
        ("steps", True, r"field 'steps'.*integer"),
        ("steps", 2.5, r"field 'steps'.*integer"),
        ("geodesic_start", math.nan, r"field 'geodesic_start'.*finite"),
        ("geodesic_start", -1.0, r"field 'geodesic_start'.*>= 0"),
        ("path_length", "far", r"field 'path_length'.*number"),
        ("geodesic_trace", [1.0, "x"], r"field 'geodesic_trace\[1\]'"),
        ("geodesic_trace", 3, r"field 'geodesic_trace'.*list"),
        ("target_ids", [-1], r"field 'target_ids\[0\]'.*>= 0"),
        ("end_reason", "bored", r"field 'end_reason'.*one of"),
        ("episode_id", 7, r"field 'episode_id'.*string"),
        ("episode_id", "", r"field 'episode_id'.*empty"),
        ("stop_instance_id", "7", r"field 'stop_instance_id'.*integer"),
        ("positions", [[0.0, math.inf, 0.0]], r"field 'positions\[0\]\[1\]'.*finite"),
        ("dialog", [{"step": 1}], r"missing field 'dialog\[0\]\.question'"),
        ("dialog", [{**ask(1).__dict__, "step": -1}], r"field 'dialog\[0\].step'.*>= 0"),
        ("dialog", "none", r"field 'dialog'.*list"),
        ("failures", {"parse": -1}, r"field 'failures\['parse'\]'.*>= 0"),
        ("failures", {"parse": "2"}, r"field 'failures\['parse'\]'.*integer"),
        ("failures", [1], r"field 'failures'.*object"),
        ("model_calls", [{"step": 0}], r"missing field 'model_calls\[0\]\.text'"),
    ],
)
def test_wrong_type_or_range_names_the_field(field: str, value: Any, message: str) -> None:
    data = valid()
    data[field] = value
    with pytest.raises(DataFormatError, match=message):
        EpisodeRecord.from_json(data)


def test_missing_and_unknown_fields_are_named() -> None:
    data = valid()
    del data["steps"]
    with pytest.raises(DataFormatError, match=r"missing field 'steps'"):
        EpisodeRecord.from_json(data)
    data = valid()
    data["stepz"] = 3
    with pytest.raises(DataFormatError, match=r"unknown field 'stepz'"):
        EpisodeRecord.from_json(data)


def test_unreachable_distance_reads_as_null_and_optional_fields_default() -> None:
    data = valid()
    data["geodesic_trace"], data["steps"] = [2.0, None], 2
    del data["positions"], data["dialog"]
    record = EpisodeRecord.from_json(data)
    assert record.geodesic_trace == [2.0, math.inf]
    assert record.dialog == []


def test_stop_facts_are_written_only_when_set_and_round_trip() -> None:
    data = valid()
    assert "stop_reason" not in data and "distractor_distance" not in data
    record = EpisodeRecord.from_json(data)  # a record written before these fields
    assert record.stop_reason is None and record.distractor_distance is None
    data |= {"stop_reason": "explored", "distractor_distance": 0.4}
    assert EpisodeRecord.from_json(json.loads(json.dumps(data))).to_json() == data


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("stop_reason", "bored", r"field 'stop_reason' must be one of candidate, explored"),
        ("stop_reason", 3, r"field 'stop_reason' must be a string"),
        ("distractor_distance", -0.5, r"field 'distractor_distance' must be >= 0"),
        ("distractor_distance", "near", r"field 'distractor_distance' must be a number"),
    ],
)
def test_bad_stop_facts_name_the_field(field: str, value: Any, message: str) -> None:
    data = valid() | {field: value}
    with pytest.raises(DataFormatError, match=message):
        EpisodeRecord.from_json(data)
