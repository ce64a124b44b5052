"""The small objects of the reference's category list: words, sane models, renders, placement.

Each category is checked for what the generator, the renderer and the oracle rely on: known
colour, material and room words, shapes that name the fine category, a deterministic model that
stands on y = 0 and fits where it is placed, that the real renderer draws, and that generated
houses place it in the rooms and on the supports it belongs to.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

from vlln.oracle.classifier.entities import MATERIAL_SYNONYMS
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Renderer
from vlln.world.catalogue import (
    cleaning,
    gadgets,
    groceries,
    keepsakes,
    kitchenware,
    personal,
    stationery,
    toiletries,
)
from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.registry import ROOM_TYPES, Catalogue, default_catalogue
from vlln.world.generator.house import generate_house
from vlln.world.materials import COLORS, MATERIALS, color_rgb, material_index
from vlln.world.mesh import Mesh

MODULES = (personal, toiletries, kitchenware, groceries, cleaning, gadgets, keepsakes, stationery)
CATEGORIES: list[Category] = [c for module in MODULES for c in module.CATEGORIES]
BY_NAME = {c.name: c for c in CATEGORIES}
REFERENCE_NAMES = (
    "shoe", "purse", "hat", "cap", "glove", "soap", "soap dispenser", "soap dish", "shampoo",
    "body loofah", "cosmetics", "hair dryer", "pan", "knife", "seasoning", "tray", "pitcher",
    "bread", "can", "jar", "wine", "detergent", "sponge", "brush", "tissue box", "tissue",
    "telephone", "camera", "tablet", "remote control", "mouse", "radio", "toy", "trophy",
    "candlestick", "mask", "notebook", "magazine", "album", "adhesive tape",
)  # fmt: skip
SCALES = (0.85, 1.15)
CEILING_HEIGHT = 2.7


def styles(category: Category, scales: tuple[float, ...] = SCALES) -> list[Style]:
    """Every shape at every scale, and every colour and material at least once."""
    shapes = list(category.shapes)
    n = max(len(shapes), len(category.colors), len(category.materials))
    drawn = {
        Style(
            category.colors[i % len(category.colors)],
            category.materials[i % len(category.materials)],
            shapes[i % len(shapes)],
            scale,
        )
        for i in range(n)
        for scale in (scales if i < len(shapes) else scales[i % len(scales) :][:1])
    }
    return sorted(drawn, key=repr)


@functools.cache
def build(name: str, style: Style, seed: int = 0) -> ObjectModel:
    return BY_NAME[name].build(style, np.random.default_rng(seed))


def size(model: ObjectModel) -> tuple[float, float, float]:
    lo, hi = model.mesh.bounds()
    return float(hi[0] - lo[0]), float(hi[1] - lo[1]), float(hi[2] - lo[2])


def test_reference_names_are_catalogue_categories() -> None:
    assert sorted(BY_NAME) == sorted(REFERENCE_NAMES)
    catalogue = default_catalogue()
    for category in CATEGORIES:
        assert catalogue.get(category.name).build is category.build


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_words_are_ones_the_oracle_knows(category: Category) -> None:
    assert set(category.colors) <= set(COLORS)
    assert set(category.materials) <= set(MATERIALS)
    assert set(category.materials) <= {*MATERIAL_SYNONYMS.values(), "plain"}
    assert category.rooms and set(category.rooms) <= set(ROOM_TYPES)
    assert all(0.0 < mean < 0.9 for mean in category.rooms.values()), "small things are few"
    for shape, fine in category.shapes.items():
        assert shape in fine.split(), f"{shape!r} should name the fine category {fine!r}"


@pytest.mark.slow
@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_every_style_builds_a_sane_model(category: Category) -> None:
    for style in styles(category):
        mesh = build(category.name, style).mesh
        assert len(mesh.positions) > 0 and len(mesh.positions) % 3 == 0
        for array in (mesh.positions, mesh.normals, mesh.uvs, mesh.colors):
            assert np.isfinite(array).all()
        np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-4)
        assert abs(float(mesh.positions[:, 1].min())) <= 1e-3, f"{style} is not on y = 0"
        assert mesh.n_triangles <= 450, (style, mesh.n_triangles)
        # The colour and material the oracle will name are drawn on the model.
        assert material_index(style.material) in mesh.materials, style
        named = np.asarray(color_rgb(style.color), np.float32)
        assert np.abs(mesh.colors - named).max(axis=1).min() <= 0.15, style


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_models_fit_where_they_are_placed(category: Category) -> None:
    for style in styles(category):
        model = build(category.name, style, 1)
        width, height, depth = size(model)
        assert max(width, height, depth) >= 0.015, style
        if category.placement is Placement.ON_SURFACE:
            assert width <= 0.4 and depth <= 0.3 and height <= 0.45, (style, size(model))
        elif category.placement is Placement.WALL_MOUNTED:
            lo, _ = model.mesh.bounds()
            assert abs(float(lo[2])) <= 1e-3, "the back must be on the wall (z = 0)"
            assert depth <= 0.2 and category.wall_height + height <= CEILING_HEIGHT - 0.3
        else:
            assert width <= 0.5 and depth <= 0.5 and height <= 0.5, (style, size(model))


@pytest.mark.parametrize("category", CATEGORIES, ids=lambda c: c.name)
def test_models_are_deterministic_and_grow_with_the_scale(category: Category) -> None:
    for shape in category.shapes:
        style = Style(category.colors[0], category.materials[0], shape, 1.0)
        a, b = (category.build(style, np.random.default_rng(5)) for _ in range(2))
        for field in ("positions", "normals", "uvs", "colors", "materials"):
            assert np.array_equal(getattr(a.mesh, field), getattr(b.mesh, field)), field
        small, large = (
            np.array(size(build(category.name, dataclasses.replace(style, scale=s))))
            for s in SCALES
        )
        assert (large >= small - 1e-6).all() and (large / small).max() >= 1.2, shape


def test_every_shape_renders_visibly_at_the_agents_resolution() -> None:
    """Each model alone on a grey floor, seen from 0.6 m: the real renderer draws it large."""
    spacing, entries, meshes = 2.0, [], []
    for category in CATEGORIES:
        for shape in category.shapes:
            style = Style(category.colors[0], category.materials[0], shape, 1.0)
            model = build(category.name, style)
            offset = (spacing * len(entries), 0.0, 0.0)
            entries.append((category.name, shape, offset, model.mesh.bounds()))
            meshes.append(model.mesh.transformed(0.0, offset).with_instance_id(len(entries)))
    spec = CameraSpec(height_m=0.5)
    with Renderer(Mesh.concatenate(meshes), spec) as renderer:
        for k, (name, shape, (x, _, _), (lo, hi)) in enumerate(entries, start=1):
            centre_y, centre_z = float(lo[1] + hi[1]) / 2, float(lo[2] + hi[2]) / 2
            tilt = -math.atan2(spec.height_m - centre_y, 0.6)
            ids = renderer.render_instance_ids((x, 0.0, centre_z + 0.6), 0.0, tilt)
            share = float((ids == k).mean())
            assert share >= 0.002, f"{name} ({shape}) covers {share:.4f} of the image"


def _boosted_catalogue() -> Catalogue:
    """The default catalogue with each small category common in its rooms."""
    boosted = {
        c.name: dataclasses.replace(c, rooms={room: 1.5 for room in c.rooms}) for c in CATEGORIES
    }
    return Catalogue([boosted.get(c.name, c) for c in default_catalogue()])


@pytest.mark.slow
def test_generated_houses_put_small_objects_where_they_belong() -> None:
    catalogue = _boosted_catalogue()
    placed: set[str] = set()
    for seed in range(3):
        house = generate_house(seed, catalogue=catalogue)
        rooms = {room.id: room for room in house.rooms}
        by_id = {inst.id: inst for inst in house.instances}
        for inst in house.instances:
            if inst.category not in BY_NAME:
                continue
            category = BY_NAME[inst.category]
            placed.add(inst.category)
            assert rooms[inst.room_id].type in category.rooms, inst.caption
            assert inst.fine_category in category.shapes.values()
            if category.placement is Placement.ON_SURFACE:
                support = by_id[inst.support_id] if inst.support_id is not None else None
                assert support is not None, inst.caption
                assert inst.attributes.placement == f"on the {support.category}"
                assert support.box.min[1] < inst.box.min[1] <= support.box.max[1] + 1e-3
                for axis in (0, 2):
                    centre = (inst.box.min[axis] + inst.box.max[axis]) / 2
                    assert support.box.min[axis] <= centre <= support.box.max[axis]
            elif category.placement is Placement.WALL_MOUNTED:
                assert inst.attributes.placement == "on the wall", inst.caption
            else:
                assert inst.box.min[1] <= 0.01, inst.caption
    assert placed == set(BY_NAME), f"never placed: {sorted(set(BY_NAME) - placed)}"


def test_the_fingerprint_follows_what_the_categories_say() -> None:
    catalogue = default_catalogue()
    assert Catalogue(list(catalogue)).fingerprint() == catalogue.fingerprint()
    assert _boosted_catalogue().fingerprint() != catalogue.fingerprint()
