"""The data benchmark prints one well-formed figure per line, consistent with each other."""

import json

import pytest

from vlln.bench.data import run_data_benchmark
from vlln.bench.settings import DataBench
from vlln.errors import ConfigError


@pytest.mark.slow
def test_data_benchmark_prints_json_lines(capsys: pytest.CaptureFixture[str]) -> None:
    figures = run_data_benchmark(DataBench(houses=1, per_house=1, as_json=True))
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert all(set(line) == {"metric", "value", "unit"} for line in lines)
    assert [f.metric for f in figures] == [line["metric"] for line in lines]
    values = {line["metric"]: line["value"] for line in lines}
    assert values["trajectories_attempted"] == 1
    assert values["trajectories_per_hour"] == pytest.approx(
        3600.0 / values["seconds_per_trajectory"], rel=1e-3
    )
    kept = values["kept_trajectories_per_hour"]
    assert kept == pytest.approx(values["trajectories_per_hour"] * values["yield"] / 100, rel=1e-3)
    if values["yield"] > 0:  # a kept trajectory: JPEG frames of both cameras, 0.02-0.1 MB each
        per_frame = values["mb_per_trajectory"] / values["frames_per_trajectory"]
        assert 0.02 < per_frame < 0.1
        per_cpu_hour = values["kept_trajectories_per_cpu_hour"]
        assert per_cpu_hour == pytest.approx(
            3600.0 / values["cpu_seconds_per_kept_trajectory"], rel=1e-2
        )
    else:
        assert values["mb_per_trajectory"] == values["frames_per_trajectory"] == 0
        assert values["kept_trajectories_per_cpu_hour"] == 0


def test_a_bad_workload_is_refused() -> None:
    with pytest.raises(ConfigError, match="--houses"):
        DataBench.build({"houses": 0, "per_house": 1})
