"""The oracle benchmark prints one well-formed figure per line for every promised metric."""

import json

import pytest

from vlln.bench.oracle import run_oracle_benchmark
from vlln.bench.service import run_service_benchmark
from vlln.bench.settings import OracleBench
from vlln.errors import ConfigError

REQUIRED = {"answer_p50_ms", "answer_p99_ms", "classify_us", "oracle_start_ms"}


@pytest.mark.slow
def test_oracle_benchmark_prints_json_lines(capsys: pytest.CaptureFixture[str]) -> None:
    figures = run_oracle_benchmark(
        OracleBench(seed=1, questions=60, service_scenes=0, as_json=True)
    )
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert all(set(line) == {"metric", "value", "unit"} for line in lines)
    values = {line["metric"]: line["value"] for line in lines}
    assert [f.metric for f in figures] == [line["metric"] for line in lines]
    assert set(values) >= REQUIRED
    per_type = {m for m in values if m.endswith("_p50_ms") and m != "answer_p50_ms"}
    assert len(per_type) >= 3  # 60 questions from the held-out mix reach several types
    for metric in per_type:
        assert metric.replace("_p50_", "_p99_") in values
    assert all(values[name] > 0 for name in REQUIRED)
    assert values["answer_p50_ms"] <= values["answer_p99_ms"]


def test_a_non_positive_question_count_is_refused() -> None:
    with pytest.raises(ConfigError, match="--questions"):
        OracleBench.build({"seed": 1, "questions": 0})


@pytest.mark.slow
def test_service_benchmark_measures_a_running_service() -> None:
    figures: dict[str, float] = {}
    run_service_benchmark(lambda metric, value, unit: figures.update({metric: value}), 1, 2, 1)
    assert figures["service_clients"] == 30 and figures["service_errors"] == 0
    assert figures["service_requests_per_s"] > 0 and figures["service_cpu_ms_per_request"] > 0
    assert 0 < figures["service_p50_ms"] <= figures["service_p99_ms"]
    assert 50 < figures["service_rss_2_scenes_mb"] < 2000
