"""The model-agent benchmark prints one well-formed figure per line for every promised metric."""

import json

import pytest

from vlln.bench.agent import run_agent_benchmark
from vlln.bench.settings import AgentBench
from vlln.errors import ConfigError

REQUIRED = {
    "prompt_build_ms",
    "output_read_ms",
    "prompt_and_read_ms",
    "level_image_ms",
    "down_image_ms",
    "request_build_ms",
    "request_kb",
}


def test_agent_benchmark_prints_json_lines(capsys: pytest.CaptureFixture[str]) -> None:
    figures = run_agent_benchmark(AgentBench(seed=1, repeats=3, as_json=True))
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [f.metric for f in figures] == [line["metric"] for line in lines]
    values = {line["metric"]: line["value"] for line in lines}
    assert set(values) >= REQUIRED
    assert values["history_images"] == 8
    assert all(values[name] > 0 for name in REQUIRED)
    assert values["prompt_and_read_ms"] == pytest.approx(
        values["prompt_build_ms"] + values["output_read_ms"], abs=0.002
    )
    assert values["request_kb"] > 10 * values["level_image_kb"]  # 11 pictures, base64


def test_a_non_positive_repeat_count_is_refused() -> None:
    with pytest.raises(ConfigError, match="--repeats"):
        AgentBench.build({"repeats": 0})
