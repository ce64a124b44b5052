"""The world benchmark prints one well-formed figure per line, with counts true of the houses."""

import json

import pytest

from vlln.bench.settings import WorldBench
from vlln.bench.world import run_world_benchmark
from vlln.errors import ConfigError
from vlln.world.generator.house import generate_house


@pytest.mark.slow
def test_world_benchmark_prints_the_mean_counts_of_the_houses(
    capsys: pytest.CaptureFixture[str],
) -> None:
    figures = run_world_benchmark(
        WorldBench(houses=2, first_seed=3, preset="small", test_houses=0, as_json=True)
    )
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [f.metric for f in figures] == [line["metric"] for line in lines]
    values = {line["metric"]: line["value"] for line in lines}
    houses = [generate_house(3), generate_house(4)]
    assert values["houses"] == 2
    assert values["categories"] >= 120
    assert values["reference_names"] >= 110
    assert values["mean_instances"] == pytest.approx(sum(len(h.instances) for h in houses) / 2)
    categories = [len({i.category for i in h.instances}) for h in houses]
    assert values["mean_categories"] == pytest.approx(sum(categories) / 2)
    assert values["mean_triangles"] > 10_000
    assert values["house_build_s"] > 0 and values["house_build_cpu_s"] > 0


@pytest.mark.parametrize(
    ("houses", "first_seed", "flag"), [(0, 0, "--houses"), (2, -1, "--first-seed")]
)
def test_bad_counts_are_refused(houses: int, first_seed: int, flag: str) -> None:
    with pytest.raises(ConfigError, match=flag):
        WorldBench.build({"houses": houses, "first_seed": first_seed})
