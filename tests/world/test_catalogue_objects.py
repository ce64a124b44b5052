"""Appliances, electronics, decor, tableware and other objects: every variant builds a sane model.

"Sane" means what the generator and the renderer rely on: a non-empty finite mesh with unit
normals, standing on y = 0, of a real-world size, within the limits of its placement (floor
objects tall enough to block the agent and lower than the ceiling, small objects that fit on a
table, wall objects with their back on the wall), deterministic, and growing with the scale.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest

from vlln.world.catalogue import decor, electronics, kitchen, misc, tableware
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.registry import ROOM_TYPES, default_catalogue
from vlln.world.materials import COLORS, MATERIALS, color_rgb, material_index

CATEGORIES: list[Category] = [
    c for module in (kitchen, electronics, decor, tableware, misc) for c in module.CATEGORIES
]
BY_NAME = {c.name: c for c in CATEGORIES}

REQUIRED = (
    "refrigerator", "stove", "microwave", "dishwasher", "washing machine", "kettle", "toaster",
    "coffee machine", "garbage", "tv", "computer monitor", "laptop", "keyboard", "printer",
    "speaker", "game console", "plant", "floor lamp", "table lamp", "ceiling light", "picture",
    "clock", "vase", "candle", "statue", "curtain", "fireplace", "cup", "bowl", "plate",
    "bottle", "book", "teapot", "fruit bowl", "piano", "guitar", "treadmill",
    "excercise equipment", "bicycle", "luggage", "basket", "box", "fan", "heater", "coat rack",
    "backpack",
)  # fmt: skip

# Plausible real-world size over the whole 0.85..1.15 scale range:
# (largest horizontal extent, height), each as (min, max) metres.
ENVELOPES: dict[str, tuple[tuple[float, float], tuple[float, float]]] = {
    "refrigerator": ((0.4, 1.1), (0.7, 2.2)),
    "stove": ((0.5, 0.9), (0.7, 1.1)),
    "microwave": ((0.25, 0.4), (0.15, 0.35)),
    "dishwasher": ((0.4, 0.8), (0.7, 1.0)),
    "washing machine": ((0.5, 0.8), (0.7, 1.2)),
    "kettle": ((0.15, 0.35), (0.15, 0.35)),
    "toaster": ((0.2, 0.4), (0.15, 0.25)),
    "coffee machine": ((0.15, 0.35), (0.25, 0.5)),
    "garbage": ((0.2, 0.45), (0.25, 0.95)),
    "tv": ((0.8, 1.5), (0.5, 1.0)),
    "computer monitor": ((0.4, 0.9), (0.3, 0.55)),
    "laptop": ((0.25, 0.4), (0.015, 0.3)),
    "keyboard": ((0.2, 0.4), (0.015, 0.05)),
    "printer": ((0.25, 0.4), (0.1, 0.35)),
    "speaker": ((0.08, 0.3), (0.12, 0.4)),
    "game console": ((0.2, 0.35), (0.05, 0.4)),
    "fan": ((0.2, 0.5), (0.7, 1.9)),
    "plant": ((0.25, 0.9), (0.3, 1.9)),
    "floor lamp": ((0.3, 1.2), (1.2, 2.2)),
    "table lamp": ((0.1, 0.3), (0.25, 0.6)),
    "ceiling light": ((0.25, 0.6), (0.05, 0.85)),
    "picture": ((0.35, 1.0), (0.35, 0.85)),
    "clock": ((0.2, 0.4), (0.2, 0.4)),
    "vase": ((0.08, 0.25), (0.15, 0.7)),
    "candle": ((0.04, 0.12), (0.07, 0.45)),
    "statue": ((0.1, 0.3), (0.2, 0.45)),
    "curtain": ((1.0, 2.3), (2.0, 2.45)),
    "fireplace": ((1.0, 1.9), (0.85, 1.35)),
    "cup": ((0.05, 0.2), (0.04, 0.16)),
    "bowl": ((0.1, 0.25), (0.03, 0.1)),
    "plate": ((0.15, 0.3), (0.01, 0.12)),
    "bottle": ((0.05, 0.1), (0.18, 0.42)),
    "book": ((0.1, 0.3), (0.015, 0.3)),
    "teapot": ((0.15, 0.3), (0.1, 0.2)),
    "fruit bowl": ((0.18, 0.3), (0.08, 0.2)),
    "piano": ((1.2, 2.3), (0.95, 1.5)),
    "guitar": ((0.25, 0.6), (0.9, 1.4)),
    "treadmill": ((1.3, 2.2), (1.0, 1.7)),
    "excercise equipment": ((0.45, 1.3), (0.45, 1.45)),
    "bicycle": ((1.4, 2.0), (0.8, 1.2)),
    "luggage": ((0.35, 0.55), (0.55, 1.15)),
    "basket": ((0.3, 0.55), (0.3, 0.7)),
    "box": ((0.3, 0.95), (0.2, 0.75)),
    "heater": ((0.5, 1.5), (0.45, 0.75)),
    "coat rack": ((0.4, 0.9), (1.5, 2.3)),
    "umbrella stand": ((0.2, 0.35), (0.6, 1.2)),
    "backpack": ((0.2, 0.35), (0.35, 0.65)),
}
FLOOR_PLACEMENTS = {Placement.AGAINST_WALL, Placement.FLOOR, Placement.AT_TABLE, Placement.CORNER}
LARGE_ON_SURFACE = {"tv", "computer monitor"}  # need a wide surface (tv stand, desk)
CEILING_HEIGHT = 2.7
TABLEWARE = {c.name for c in tableware.CATEGORIES}
COMMON = ("plant", "picture", "table lamp", "cup", "bottle", "book", "garbage")
RARE = (
    "piano",
    "guitar",
    "fireplace",
    "treadmill",
    "excercise equipment",
    "bicycle",
    "game console",
)
SCALES = (0.85, 1.15)


def sample_styles(category: Category, scales: tuple[float, ...] = SCALES) -> list[Style]:
    """Every colour and material at least once, and every shape at every given scale."""
    shapes = list(category.shapes)
    n = max(len(shapes), len(category.colors), len(category.materials))
    styles = {
        Style(
            category.colors[i % len(category.colors)],
            category.materials[i % len(category.materials)],
            shapes[i % len(shapes)],
            scale,
        )
        for i in range(n)
        for scale in (scales if i < len(shapes) else scales[i % len(scales) : i % len(scales) + 1])
    }
    return sorted(styles, key=repr)


def size_cases(category: Category) -> list[tuple[Style, int]]:
    """The sampled styles, plus every shape at both extreme scales with a second seed."""
    shapes = [
        Style(category.colors[0], category.materials[0], shape, scale)
        for shape in category.shapes
        for scale in SCALES
    ]
    return [(style, 0) for style in sample_styles(category)] + [(style, 1) for style in shapes]


@functools.cache
def build(category_name: str, style: Style, seed: int) -> ObjectModel:
    """A model, built once per test session (tests only read it)."""
    return BY_NAME[category_name].build(style, np.random.default_rng(seed))


def extents(model: ObjectModel) -> tuple[float, float, float]:
    lo, hi = model.mesh.bounds()
    size = hi - lo
    return float(size[0]), float(size[1]), float(size[2])


def test_required_categories_are_provided_once() -> None:
    names = [c.name for c in CATEGORIES]
    assert len(names) == len(set(names))
    assert set(REQUIRED) <= set(names)
    assert set(ENVELOPES) == set(names), "every category needs a size envelope here"


def test_default_catalogue_registers_every_category() -> None:
    catalogue = default_catalogue()
    for category in CATEGORIES:
        assert catalogue.get(category.name).build is category.build


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_declared_variants_use_known_words(category: Category) -> None:
    assert category.name == category.name.lower().strip()
    assert category.shapes and all(category.shapes.values())
    assert category.colors and set(category.colors) <= set(COLORS)
    assert category.materials and set(category.materials) <= set(MATERIALS)
    assert category.rooms and set(category.rooms) <= set(ROOM_TYPES)
    assert all(count > 0.0 for count in category.rooms.values())


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_every_declared_style_builds_a_sane_mesh(category: Category) -> None:
    for style in sample_styles(category):
        mesh = build(category.name, style, seed=0).mesh
        n = len(mesh.positions)
        assert n > 0 and n % 3 == 0
        for array in (mesh.positions, mesh.normals, mesh.uvs, mesh.colors):
            assert len(array) == n and np.isfinite(array).all()
        np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-4)
        assert mesh.colors.min() >= 0.0 and mesh.colors.max() <= 1.0
        assert mesh.materials.min() >= 0 and mesh.materials.max() < len(MATERIALS)
        assert not mesh.instance_ids.any()
        assert abs(float(mesh.positions[:, 1].min())) <= 1e-3, f"{style} does not stand on y=0"
        # The words an oracle will say about the instance must be visible on it.
        assert material_index(style.material) in mesh.materials, style
        named = np.asarray(color_rgb(style.color), np.float32)
        assert np.abs(mesh.colors - named).max(axis=1).min() <= 0.15, style


@pytest.mark.slow
@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_models_respect_their_placement_limits(category: Category) -> None:
    for style, seed in size_cases(category):
        model = build(category.name, style, seed)
        lo, hi = model.mesh.bounds()
        width, height, depth = extents(model)
        if category.placement in FLOOR_PLACEMENTS:
            assert 0.2 <= height <= 2.4, f"{style}: {height:.2f} m tall"
            assert lo[0] <= 0.0 <= hi[0] and lo[2] <= 0.0 <= hi[2], "origin off the base"
        elif category.placement is Placement.ON_SURFACE:
            if category.name not in LARGE_ON_SURFACE:
                assert width <= 0.4 and depth <= 0.3, f"{style}: {width:.3f} x {depth:.3f}"
        elif category.placement is Placement.WALL_MOUNTED:
            assert abs(float(lo[2])) <= 1e-3, "the back must be on the wall (z = 0)"
            assert depth <= 0.3
            assert category.wall_height >= 0.0
            assert category.wall_height + height <= CEILING_HEIGHT - 0.1
        elif category.placement is Placement.CEILING:
            assert height <= 0.85, "a person must walk under it"


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_models_have_real_world_sizes(category: Category) -> None:
    (extent_lo, extent_hi), (height_lo, height_hi) = ENVELOPES[category.name]
    for style, seed in size_cases(category):
        width, height, depth = extents(build(category.name, style, seed))
        assert extent_lo <= max(width, depth) <= extent_hi, (style, width, depth)
        assert height_lo <= height <= height_hi, (style, height)


def test_triangle_counts_stay_small_enough_for_a_cpu_rasteriser() -> None:
    counts: dict[str, list[int]] = {}
    for category in CATEGORIES:
        for style in sample_styles(category):
            n = build(category.name, style, seed=0).mesh.n_triangles
            counts.setdefault(category.name, []).append(n)
    for name, numbers in counts.items():
        assert max(numbers) <= (300 if name in TABLEWARE else 450), (name, max(numbers))
    assert np.mean([np.mean(v) for v in counts.values()]) <= 200


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_scale_changes_size(category: Category) -> None:
    for shape in category.shapes:
        small, large = (
            build(category.name, Style(category.colors[0], category.materials[0], shape, s), 0)
            for s in SCALES
        )
        small_size, large_size = np.array(extents(small)), np.array(extents(large))
        assert (large_size >= small_size - 1e-6).all(), shape
        assert (large_size / small_size).max() >= 1.2, shape


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_same_style_and_seed_give_identical_models(category: Category) -> None:
    for style in sample_styles(category, (1.0,))[:1]:
        a, b = (category.build(style, np.random.default_rng(11)) for _ in range(2))
        for name in ("positions", "normals", "uvs", "colors", "materials", "instance_ids"):
            assert np.array_equal(getattr(a.mesh, name), getattr(b.mesh, name)), name
        assert a.surfaces == b.surfaces


@pytest.mark.parametrize(
    "category", [c for c in CATEGORIES if c.placement in FLOOR_PLACEMENTS], ids=lambda c: c.name
)
def test_support_surfaces_are_tops_of_the_model(category: Category) -> None:
    for style in sample_styles(category):
        model = build(category.name, style, seed=0)
        lo, hi = model.mesh.bounds()
        for surface in model.surfaces:
            (x, z), (w, d) = surface.center, surface.size
            assert 0.2 <= surface.height <= hi[1] + 1e-3
            assert lo[0] - 1e-3 <= x - w / 2 and x + w / 2 <= hi[0] + 1e-3
            assert lo[2] - 1e-3 <= z - d / 2 and z + d / 2 <= hi[2] + 1e-3
            at_top = np.abs(model.mesh.positions[:, 1] - surface.height) <= 0.002
            assert at_top.any(), f"{style}: nothing at the surface height {surface.height:.3f}"


def test_surface_models_offer_their_tops() -> None:
    for name in ("refrigerator", "dishwasher", "fireplace", "stove", "piano"):
        category = BY_NAME[name]
        style = Style(category.colors[0], category.materials[0], next(iter(category.shapes)))
        assert build(category.name, style, seed=0).surfaces, name


def test_common_things_are_common_and_rare_things_rare() -> None:
    for name in COMMON:
        assert sum(BY_NAME[name].rooms.values()) >= 2.0, name
    for name in RARE:
        everyday = {room: n for room, n in BY_NAME[name].rooms.items() if room != "gym"}
        assert sum(everyday.values()) <= 0.6, name
    assert set(BY_NAME["ceiling light"].rooms) == set(ROOM_TYPES)


def test_random_details_vary_with_the_seed() -> None:
    for name in ("plant", "picture", "bicycle", "book"):
        category = BY_NAME[name]
        style = Style(category.colors[0], category.materials[0], next(iter(category.shapes)))
        a, b = build(name, style, seed=0), build(name, style, seed=1)
        assert not (
            a.mesh.positions.shape == b.mesh.positions.shape
            and np.array_equal(a.mesh.positions, b.mesh.positions)
        ), name
