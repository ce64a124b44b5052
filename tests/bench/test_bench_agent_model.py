"""`vlln bench agent`, the model part: the tiny model's decision rates, and a plain note that
no GPU figures were measured."""

from __future__ import annotations

import json

import pytest
import torch

from vlln.bench.agent_model import BATCH, run_model_benchmark
from vlln.bench.settings import AgentBench


@pytest.mark.slow
def test_the_tiny_model_figures_are_measured_and_printed(
    capsys: pytest.CaptureFixture[str],
) -> None:
    figures = run_model_benchmark(AgentBench(as_json=True), passes=1, max_new_tokens=8)
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    printed = {line["metric"]: line["value"] for line in lines if "metric" in line}
    assert printed == {figure.metric: round(figure.value, 3) for figure in figures}
    device = "cuda" if torch.cuda.is_available() else "cpu"
    assert f"tiny_model_steps_per_s_{device}_threads1" in printed
    assert f"tiny_model_batch{BATCH}_steps_per_s_{device}_threads1" in printed
    assert all(value > 0 for value in printed.values())
    notes = [line["note"] for line in lines if "note" in line]
    assert notes and "no Qwen2.5-VL-3B figures" in notes[0]
