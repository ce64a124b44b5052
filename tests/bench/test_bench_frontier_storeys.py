import json

import pytest

from vlln.bench.frontier_storeys import run_frontier_storeys_benchmark
from vlln.bench.settings import FrontierStoreysBench
from vlln.errors import ConfigError


@pytest.mark.slow
def test_the_benchmark_splits_the_success_rate_by_the_targets_storey(
    capsys: pytest.CaptureFixture[str],
) -> None:
    figures = {
        f.metric: f.value
        for f in run_frontier_storeys_benchmark(
            FrontierStoreysBench(houses=1, floors=2, episodes=1, as_json=True)
        )
    }
    assert figures["frontier_iign_episodes"] == 1
    assert figures["frontier_iign_success_rate"] in (0.0, 100.0)
    assert figures["other_storey_successes"] <= figures["targets_on_other_storey"] <= 1
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [line["metric"] for line in lines] == list(figures)


def test_one_storey_is_refused() -> None:
    with pytest.raises(ConfigError, match="--floors"):
        FrontierStoreysBench.build({"floors": 1})
