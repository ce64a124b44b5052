"""``vlln bench world``: what the catalogue holds, how rich and how costly the houses are.

The catalogue decides how many objects a house holds, and every object costs build time,
triangles to render and oracle knowledge to index; these figures let a catalogue change be
judged on the same seeds before and after. Instance and category counts do not depend on the
machine; the build time is reported both as wall and as CPU seconds, the latter being less
disturbed by other work on a shared machine.
"""

from __future__ import annotations

import statistics
import time

from vlln.bench.figures import Figure, emit
from vlln.bench.settings import WorldBench
from vlln.bench.world_fidelity import preset_statistics, print_comparison
from vlln.world.catalogue import default_catalogue
from vlln.world.catalogue.reference import REFERENCE_CATEGORIES
from vlln.world.generator.presets import generate_preset_house


def run_world_benchmark(settings: WorldBench) -> list[Figure]:
    """Build houses ``first_seed .. first_seed + houses - 1`` of ``preset`` and print their
    mean figures; with ``test_houses``, then each anchored statistic of that many test houses
    and their episodes beside its Matterport3D anchor (:mod:`vlln.bench.world_fidelity`)."""
    houses, first_seed, preset = settings.houses, settings.first_seed, settings.preset
    as_json, test_houses = settings.as_json, settings.test_houses
    instances, categories, triangles, walls, cpus = [], [], [], [], []
    for seed in range(first_seed, first_seed + houses):
        cpu_start, wall_start = time.process_time(), time.perf_counter()
        house = generate_preset_house(seed, preset)
        walls.append(time.perf_counter() - wall_start)
        cpus.append(time.process_time() - cpu_start)
        instances.append(len(house.instances))
        categories.append(len({inst.category for inst in house.instances}))
        triangles.append(0 if house.geometry is None else house.geometry.mesh.n_triangles)
    catalogue = default_catalogue()
    figures = [
        Figure("categories", len(catalogue), "categories"),
        Figure("reference_names", len(set(catalogue.names) & set(REFERENCE_CATEGORIES)), "of 115"),
        Figure("houses", float(houses), "houses"),
        Figure("mean_instances", statistics.mean(instances), "objects/house"),
        Figure("mean_categories", statistics.mean(categories), "categories/house"),
        Figure("mean_triangles", statistics.mean(triangles), "triangles/house"),
        Figure("house_build_s", statistics.median(walls), "s (median wall)"),
        Figure("house_build_cpu_s", statistics.median(cpus), "s (median CPU)"),
    ]
    for figure in figures:
        emit(figure, as_json)
    if test_houses > 0:
        print_comparison(preset_statistics(preset, test_houses), as_json)
    return figures
