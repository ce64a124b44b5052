"""Furniture and fixture categories: every declared variant builds a sane, standing model."""

from __future__ import annotations

import numpy as np
import pytest

from vlln.world.catalogue import bathroom, bedroom, seating, storage, tables
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style, Surface
from vlln.world.catalogue.registry import ROOM_TYPES, Catalogue
from vlln.world.materials import COLORS, MATERIALS

CATEGORIES: list[Category] = [
    c for module in (seating, tables, storage, bedroom, bathroom) for c in module.CATEGORIES
]
BY_NAME = {c.name: c for c in CATEGORIES}

# Plausible real-world size of each category, over the whole 0.85..1.15 scale range:
# (largest horizontal extent, height), each as (min, max) metres.
ENVELOPES: dict[str, tuple[tuple[float, float], tuple[float, float]]] = {
    "chair": ((0.35, 0.75), (0.7, 1.2)),
    "armchair": ((0.65, 1.1), (0.65, 1.3)),
    "couch": ((1.2, 3.0), (0.65, 1.05)),
    "stool": ((0.25, 0.5), (0.35, 0.95)),
    "bench": ((0.9, 1.7), (0.35, 0.6)),
    "ottoman": ((0.4, 0.7), (0.3, 0.55)),
    "beanbag": ((0.6, 1.1), (0.35, 0.8)),
    "table": ((0.7, 2.0), (0.6, 0.9)),
    "coffee table": ((0.6, 1.4), (0.3, 0.55)),
    "desk": ((0.9, 1.7), (0.6, 0.9)),
    "side table": ((0.35, 0.65), (0.45, 0.72)),
    "kitchen island": ((1.2, 2.3), (0.75, 1.1)),
    "tv stand": ((1.1, 2.1), (0.4, 0.6)),
    "cabinet": ((0.6, 1.9), (0.65, 2.3)),
    "wardrobe": ((0.8, 1.85), (1.6, 2.4)),
    "bookshelf": ((0.65, 1.2), (0.7, 2.1)),
    "dresser": ((1.0, 1.55), (0.65, 1.9)),
    "drawer": ((0.65, 1.0), (0.85, 1.5)),
    "shelf": ((0.45, 1.1), (0.1, 0.45)),
    "shoe rack": ((0.6, 1.0), (0.4, 1.15)),
    "counter": ((1.5, 3.0), (0.75, 1.05)),
    "bed": ((1.7, 2.5), (0.8, 1.4)),
    "nightstand": ((0.35, 0.65), (0.45, 0.7)),
    "crib": ((1.0, 1.5), (0.75, 1.2)),
    "pillow": ((0.35, 0.8), (0.1, 0.2)),
    "rug": ((1.2, 3.3), (0.005, 0.02)),
    "toilet": ((0.5, 0.85), (0.65, 1.0)),
    "sink": ((0.4, 1.25), (0.8, 1.25)),
    "bathtub": ((1.3, 2.2), (0.45, 0.9)),
    "shower": ((0.7, 1.5), (1.6, 2.4)),
    "towel": ((0.3, 0.85), (0.35, 0.95)),
    "mirror": ((0.45, 0.9), (0.5, 1.0)),
    "toilet paper": ((0.1, 0.25), (0.15, 0.35)),
    "bath mat": ((0.45, 1.05), (0.005, 0.02)),
    "hamper": ((0.35, 0.65), (0.4, 0.8)),
}
FLAT_FLOOR_CATEGORIES = {"rug", "bath mat"}
FLOOR_PLACEMENTS = {Placement.AGAINST_WALL, Placement.FLOOR, Placement.AT_TABLE, Placement.CORNER}
COMMON = ("chair", "table", "cabinet", "couch", "bed", "pillow", "towel", "sink", "toilet", "shelf")


def sample_styles(category: Category) -> list[Style]:
    """Enough styles to use every shape, colour and material once, at three scales."""
    shapes = list(category.shapes)
    n = max(len(shapes), len(category.colors), len(category.materials))
    scales = (0.85, 1.0, 1.15)
    return [
        Style(
            category.colors[i % len(category.colors)],
            category.materials[i % len(category.materials)],
            shapes[i % len(shapes)],
            scales[i % len(scales)],
        )
        for i in range(n)
    ]


def build(category: Category, style: Style, seed: int) -> ObjectModel:
    return category.build(style, np.random.default_rng(seed))


def supported_fraction(model: ObjectModel, surface: Surface) -> float:
    """Share of a 5x5 grid of points on the surface that lie on upward faces at its height."""
    pos = model.mesh.positions.reshape(-1, 3, 3).astype(np.float64)
    up = model.mesh.normals.reshape(-1, 3, 3)[:, :, 1].mean(axis=1) > 0.9
    level = np.abs(pos[:, :, 1] - surface.height).max(axis=1) < 0.003
    tris = pos[up & level][:, :, [0, 2]]
    (cx, cz), (w, d) = surface.center, surface.size
    grid = np.linspace(-0.45, 0.45, 5)
    points = np.array([(cx + u * w, cz + v * d) for u in grid for v in grid])
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]

    def cross(o: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
        return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (
            q[..., 0] - o[..., 0]
        )

    pts = points[:, None, :]
    s1, s2, s3 = cross(a, b, pts), cross(b, c, pts), cross(c, a, pts)
    eps = 1e-9
    inside = ((s1 >= -eps) & (s2 >= -eps) & (s3 >= -eps)) | (
        (s1 <= eps) & (s2 <= eps) & (s3 <= eps)
    )
    return float(inside.any(axis=1).mean())


def test_the_furniture_categories_are_all_there() -> None:
    assert set(ENVELOPES) <= set(BY_NAME)
    assert len(Catalogue(CATEGORIES)) == len(CATEGORIES)  # no name is defined twice


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_declarations_use_known_words(category: Category) -> None:
    assert category.name == category.name.lower().strip()
    assert category.shapes and category.colors and category.materials
    assert set(category.colors) <= set(COLORS)
    assert set(category.materials) <= set(MATERIALS)
    assert category.rooms
    assert set(category.rooms) <= set(ROOM_TYPES)
    assert all(mean > 0 for mean in category.rooms.values())
    if category.placement is Placement.WALL_MOUNTED:
        assert 0.3 < category.wall_height < 2.3


def test_common_categories_are_common() -> None:
    for name in COMMON:
        assert sum(BY_NAME[name].rooms.values()) >= 1.0, name
    assert BY_NAME["bed"].rooms["bedroom"] >= 1.0
    assert BY_NAME["toilet"].rooms["bathroom"] >= 1.0
    assert BY_NAME["toilet"].rooms["toilet"] >= 1.0


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_every_variant_builds_a_sane_standing_model(category: Category) -> None:
    (min_extent, max_extent), (min_h, max_h) = ENVELOPES[category.name]
    for seed, style in enumerate(sample_styles(category)):
        mesh = build(category, style, seed).mesh
        label = f"{category.name} {style}"
        assert mesh.n_triangles > 0, label
        assert mesh.n_triangles <= 450, label
        arrays = (mesh.positions, mesh.normals, mesh.uvs, mesh.colors)
        assert all(np.isfinite(a).all() for a in arrays), label
        assert len(mesh.positions) % 3 == 0
        assert ((mesh.colors >= 0.0) & (mesh.colors <= 1.0)).all(), label
        assert ((mesh.materials >= 0) & (mesh.materials < len(MATERIALS))).all(), label
        np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-4)
        lo, hi = mesh.bounds()
        assert abs(float(lo[1])) <= 0.001, label
        size = hi - lo
        assert min_extent <= max(size[0], size[2]) <= max_extent, (label, size)
        assert min_h <= size[1] <= max_h, (label, size)
        centre = (lo + hi) / 2
        assert abs(centre[0]) <= 0.03 and abs(centre[2]) <= 0.03, (label, centre)


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_triangles_face_the_way_their_normals_say(category: Category) -> None:
    style = sample_styles(category)[0]
    mesh = build(category, style, 0).mesh
    tri = mesh.positions.reshape(-1, 3, 3).astype(np.float64)
    geometric = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    real = np.linalg.norm(geometric, axis=1) > 1e-10
    stored = mesh.normals.reshape(-1, 3, 3).mean(axis=1)
    assert ((geometric * stored).sum(axis=1)[real] > 0).all()


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_floor_objects_are_walkable_or_visible_obstacles(category: Category) -> None:
    if category.placement not in FLOOR_PLACEMENTS:
        return
    for seed, style in enumerate(sample_styles(category)):
        lo, hi = build(category, style, seed).mesh.bounds()
        height = float(hi[1] - lo[1])
        if category.name in FLAT_FLOOR_CATEGORIES:
            assert height <= 0.02, (category.name, style)
        else:
            assert 0.2 <= height <= 2.4, (category.name, style)


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_surfaces_lie_on_real_tops_inside_the_footprint(category: Category) -> None:
    for seed, style in enumerate(sample_styles(category)):
        model = build(category, style, seed)
        lo, hi = model.mesh.bounds()
        for surface in model.surfaces:
            (cx, cz), (w, d) = surface.center, surface.size
            label = (category.name, style, surface)
            assert w > 0.05 and d > 0.05, label
            assert lo[0] - 1e-4 <= cx - w / 2 and cx + w / 2 <= hi[0] + 1e-4, label
            assert lo[2] - 1e-4 <= cz - d / 2 and cz + d / 2 <= hi[2] + 1e-4, label
            assert 0.0 < surface.height <= hi[1] + 1e-6, label
            assert supported_fraction(model, surface) >= 0.8, label


@pytest.mark.parametrize(
    "name",
    ["table", "desk", "counter", "bookshelf", "shelf", "nightstand", "dresser", "bed",
     "couch", "drawer", "coffee table", "side table", "kitchen island", "tv stand"],
)  # fmt: skip
def test_furniture_with_a_top_offers_a_surface(name: str) -> None:
    category = BY_NAME[name]
    for shape in category.shapes:
        style = Style(category.colors[0], category.materials[0], shape)
        assert build(category, style, 0).surfaces, (name, shape)


def test_pillows_and_towels_go_where_people_put_them() -> None:
    assert BY_NAME["pillow"].placement is Placement.ON_SURFACE
    for name in ("towel", "mirror", "toilet paper", "shelf"):
        assert BY_NAME[name].placement is Placement.WALL_MOUNTED, name


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_scale_changes_size(category: Category) -> None:
    shape = next(iter(category.shapes))
    small = build(category, Style(category.colors[0], category.materials[0], shape, 0.85), 7)
    large = build(category, Style(category.colors[0], category.materials[0], shape, 1.15), 7)
    lo_s, hi_s = small.mesh.bounds()
    lo_l, hi_l = large.mesh.bounds()
    assert ((hi_l - lo_l) >= (hi_s - lo_s) - 1e-6).all()
    assert float(np.prod(hi_l - lo_l)) > 1.5 * float(np.prod(hi_s - lo_s))


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_same_style_and_seed_give_identical_models(category: Category) -> None:
    for seed, style in enumerate(sample_styles(category)[:3]):
        first, second = build(category, style, seed), build(category, style, seed)
        for name in ("positions", "normals", "uvs", "colors", "materials", "instance_ids"):
            np.testing.assert_array_equal(getattr(first.mesh, name), getattr(second.mesh, name))
        assert first.surfaces == second.surfaces


def test_shapes_look_different() -> None:
    for category in CATEGORIES:
        if len(category.shapes) < 2:
            continue
        meshes = [
            build(category, Style(category.colors[0], category.materials[0], shape), 0).mesh
            for shape in category.shapes
        ]
        signatures = {(m.n_triangles, *np.round(m.bounds()[1], 3)) for m in meshes}
        assert len(signatures) == len(meshes), category.name


def test_every_room_type_gets_some_furniture() -> None:
    for room_type in ROOM_TYPES:
        assert any(room_type in c.rooms for c in CATEGORIES), room_type
