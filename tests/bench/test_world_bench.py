"""``vlln bench world`` reports the catalogue and what houses cost."""

from __future__ import annotations

import json

import pytest

from vlln.bench.world import run_world_benchmark


def test_world_figures_describe_the_catalogue_and_the_houses(
    capsys: pytest.CaptureFixture[str],
) -> None:
    figures = {f.metric: f.value for f in run_world_benchmark(houses=1, as_json=True)}
    assert figures["categories"] >= 100
    assert figures["reference_names"] >= 70
    assert figures["objects_per_house"] > 20
    assert figures["house_build_cpu_s"] > 0.0
    printed = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [p["metric"] for p in printed] == list(figures)
