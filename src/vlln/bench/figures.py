"""How benchmarks print their figures: one JSON object per line, or an aligned table."""

from __future__ import annotations

import json
import statistics
import time
from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Figure:
    metric: str
    value: float
    unit: str


def emit(figure: Figure, as_json: bool) -> None:
    """Print a figure as soon as it is measured, so a long benchmark shows progress."""
    value = round(figure.value, 3)
    if as_json:
        print(json.dumps({"metric": figure.metric, "value": value, "unit": figure.unit}))
    else:
        print(f"{figure.metric:<22} {value:>12.3f} {figure.unit}")


def median_seconds(run: Callable[[], object], repeats: int) -> float:
    """Median wall time of ``repeats`` calls; the median resists a busy neighbour."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)
