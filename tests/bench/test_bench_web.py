"""`vlln bench web` measures key presses in a real browser (a handful here)."""

from __future__ import annotations

import json

import pytest

from vlln.cli import main


@pytest.mark.slow
def test_bench_web_reports_key_to_frame_latency(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "web", "--presses", "10", "--json"]) == 0
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    figures = {line["metric"]: line["value"] for line in lines}
    assert figures["key_presses"] == 10
    assert 0 < figures["key_to_frame_p50_ms"] <= figures["key_to_frame_p99_ms"]
    assert main(["bench", "web", "--presses", "3"]) == 2
