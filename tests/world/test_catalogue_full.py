"""The whole catalogue: the reference's names, distinct vocabularies, and every category seen
by the renderer; the newer categories' models are sane and of real-world size."""

from __future__ import annotations

import collections
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from vlln.errors import ConfigError
from vlln.sim.camera import CameraSpec
from vlln.viz.catalogue_sheet import render_category, write_catalogue_sheet
from vlln.world.catalogue import appliances, fixtures, household, leisure, textiles
from vlln.world.catalogue.base import Category, Placement, Style
from vlln.world.catalogue.reference import NOT_IN_A_HOUSE, REFERENCE_CATEGORIES
from vlln.world.catalogue.registry import ROOM_TYPES, Catalogue, default_catalogue
from vlln.world.materials import COLORS, MATERIALS, color_rgb, material_index

NEW: list[Category] = [
    c for module in (appliances, household, textiles, fixtures, leisure) for c in module.CATEGORIES
]
# (largest horizontal extent, height), each as (min, max) metres, over the 0.85..1.15 scales.
ENVELOPES: dict[str, tuple[tuple[float, float], tuple[float, float]]] = {
    "oven": ((0.5, 0.75), (1.0, 1.8)),
    "range hood": ((0.5, 1.05), (0.15, 0.95)),
    "clothes dryer": ((0.5, 0.75), (0.55, 1.0)),
    "air conditioner": ((0.65, 1.3), (0.2, 0.35)),
    "water cooler": ((0.25, 0.45), (1.0, 1.6)),
    "water heater": ((0.35, 0.7), (1.0, 2.0)),
    "footstool": ((0.3, 0.6), (0.25, 0.6)),
    "vanity": ((0.65, 1.55), (0.85, 1.25)),
    "countertop": ((1.0, 1.9), (0.7, 1.25)),
    "stand": ((0.25, 0.5), (0.8, 1.25)),
    "ladder": ((0.35, 1.1), (1.2, 2.45)),
    "cart": ((0.35, 1.0), (0.6, 0.95)),
    "pool table": ((1.7, 2.9), (0.7, 1.0)),
    "cushion": ((0.3, 0.6), (0.08, 0.22)),
    "blanket": ((0.4, 0.7), (0.08, 0.24)),
    "sheet": ((0.3, 0.45), (0.02, 0.13)),
    "blinds": ((0.75, 1.55), (1.1, 1.55)),
    "switch": ((0.07, 0.2), (0.07, 0.11)),
    "socket": ((0.07, 0.2), (0.07, 0.11)),
    "plug": ((0.07, 0.35), (0.3, 0.5)),
    "hook": ((0.06, 0.8), (0.08, 0.17)),
    "hanger": ((0.35, 0.6), (0.18, 0.8)),
    "sign": ((0.25, 0.45), (0.12, 0.5)),
    "blackboard": ((0.65, 1.4), (0.5, 1.05)),
    "drum": ((0.35, 1.7), (0.45, 1.4)),
    "umbrella": ((0.1, 1.2), (0.35, 1.1)),
    "person": ((0.35, 0.8), (0.95, 2.15)),
}
SCALES = (0.85, 1.15)
FLOOR = {Placement.AGAINST_WALL, Placement.FLOOR, Placement.AT_TABLE, Placement.CORNER}


def styles(category: Category) -> list[Style]:
    """Every shape at both extreme scales, and every colour and material at least once."""
    shapes = list(category.shapes)
    n = max(len(category.colors), len(category.materials))
    varied = [
        Style(
            category.colors[i],
            category.materials[i % len(category.materials)],
            shapes[i % 2 % len(shapes)],
        )
        for i in range(min(n, len(category.colors)))
    ]
    extremes = [
        Style(category.colors[0], category.materials[0], shape, scale)
        for shape in shapes
        for scale in SCALES
    ]
    return extremes + varied


def test_the_catalogue_uses_the_reference_names() -> None:
    names = set(default_catalogue().names)
    assert not names & set(NOT_IN_A_HOUSE)
    assert len(REFERENCE_CATEGORIES) == len(set(REFERENCE_CATEGORIES)) == 115
    assert len(names & set(REFERENCE_CATEGORIES)) >= 70


def test_fine_categories_are_distinct_across_the_catalogue() -> None:
    catalogue = default_catalogue()
    fine = collections.Counter(f for c in catalogue for f in c.shapes.values())
    assert [f for f, n in fine.items() if n > 1] == []
    clashes = [(c.name, f) for c in catalogue for f in c.shapes.values() if f != c.name]
    assert [(name, f) for name, f in clashes if f in catalogue.names] == []


@pytest.mark.parametrize("category", NEW, ids=lambda c: c.name)
def test_new_models_are_sane_and_real_sized(category: Category) -> None:
    assert category.colors and set(category.colors) <= set(COLORS)
    assert category.materials and set(category.materials) <= set(MATERIALS)
    assert category.rooms and set(category.rooms) <= set(ROOM_TYPES)
    (extent_lo, extent_hi), (height_lo, height_hi) = ENVELOPES[category.name]
    for style in styles(category):
        model = category.build(style, np.random.default_rng(0))
        mesh = model.mesh
        assert len(mesh.positions) > 0 and np.isfinite(mesh.positions).all()
        np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-4)
        assert mesh.colors.min() >= 0.0 and mesh.colors.max() <= 1.0
        assert mesh.n_triangles <= 600, (style, mesh.n_triangles)
        lo, hi = mesh.bounds()
        assert abs(float(lo[1])) <= 1e-3, f"{style} does not stand on y=0"
        assert material_index(style.material) in mesh.materials, style
        named = np.asarray(color_rgb(style.color), np.float32)
        assert np.abs(mesh.colors - named).max(axis=1).min() <= 0.15, style
        width, height, depth = (float(v) for v in hi - lo)
        assert extent_lo <= max(width, depth) <= extent_hi, (style, width, depth)
        assert height_lo <= height <= height_hi, (style, height)
        if category.placement is Placement.WALL_MOUNTED:
            assert abs(float(lo[2])) <= 1e-3, "the back must be on the wall (z = 0)"
            assert category.wall_height + height <= 2.6
        elif category.placement in FLOOR:
            assert lo[0] <= 0.0 <= hi[0] and lo[2] <= 0.0 <= hi[2], "origin off the base"
        for surface in model.surfaces:
            assert np.any(np.abs(mesh.positions[:, 1] - surface.height) <= 0.002), style


@pytest.mark.slow
def test_every_category_is_seen_by_the_renderer() -> None:
    spec = CameraSpec(width=160, height=120)
    for category in default_catalogue():
        view = render_category(category, spec)
        assert view.rgb.shape == (120, 160, 3)
        assert view.object_pixels >= 0.005 * 160 * 120, (category.name, view.object_pixels)


def test_the_contact_sheet_tiles_every_category(tmp_path: Path) -> None:
    catalogue = Catalogue([default_catalogue().get(name) for name in ("person", "socket")])
    sheet = write_catalogue_sheet(catalogue, tmp_path)
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "catalogue.png",
        "person.png",
        "socket.png",
    ]
    assert Image.open(tmp_path / "person.png").size == (640, 480)
    image = np.asarray(Image.open(sheet))
    assert image.shape[0] >= 160 and image.shape[1] >= 2 * 213


def test_the_sheet_wants_a_folder(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    with pytest.raises(ConfigError, match="is a file, not a folder"):
        write_catalogue_sheet(default_catalogue(), tmp_path / "file")
