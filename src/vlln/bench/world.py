"""Figures of the procedural houses: what the catalogue holds and what a house costs to build.

The build time is CPU seconds of this process (``time.process_time``), so that other work on
a shared machine does not move it; objects per house show how full the catalogue makes them.
"""

from __future__ import annotations

import statistics
import time

from vlln.bench.figures import Figure, emit
from vlln.world.catalogue import default_catalogue
from vlln.world.catalogue.reference import REFERENCE_CATEGORIES
from vlln.world.generator import generate_house


def run_world_benchmark(houses: int = 20, as_json: bool = False) -> list[Figure]:
    """Build houses ``0..houses-1`` and print the catalogue and per-house figures."""
    catalogue = default_catalogue()
    names = set(catalogue.names)
    figures = [
        Figure("categories", len(catalogue), "categories"),
        Figure("reference_names", len(names & set(REFERENCE_CATEGORIES)), "of 115"),
    ]
    for figure in figures:
        emit(figure, as_json)
    generate_house(0)  # warm up: imports and cached tables are no part of a house's cost
    objects, cpu = [], []
    for seed in range(houses):
        started = time.process_time()
        house = generate_house(seed)
        cpu.append(time.process_time() - started)
        objects.append(len(house.instances))
    for figure in (
        Figure("objects_per_house", statistics.mean(objects), "objects"),
        Figure("house_build_cpu_s", statistics.mean(cpu), "s"),
    ):
        figures.append(figure)
        emit(figure, as_json)
    return figures
