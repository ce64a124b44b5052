"""Balancing: the caps, the flatness figures, the determinism and the report."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from vlln.datagen.balance import BalanceConfig, flatness, select
from vlln.datagen.balance.report import write_report
from vlln.datagen.balance.select import Item


def skewed_items(seed: int = 3) -> list[Item]:
    """A crowded dataset: scenes with 60, 25, 10, 5 and 2 trajectories, categories drawn with
    Zipf-like weights, so a few scenes and categories dominate."""
    rng = np.random.default_rng(seed)
    categories = [f"category_{k:02d}" for k in range(20)]
    weights = 1.0 / np.arange(1, 21)
    items = []
    for scene, count in zip(("a", "b", "c", "d", "e"), (60, 25, 10, 5, 2), strict=True):
        for index in range(count):
            category = categories[int(rng.choice(20, p=weights / weights.sum()))]
            items.append(Item(f"house_{scene}", index, f"house_{scene}", category))
    return items


def test_flatness_of_even_and_uneven_counts() -> None:
    even = flatness({"a": 4, "b": 4, "c": 4})
    assert (even.gini, even.max_over_mean) == (0.0, 1.0)
    one = flatness({"a": 9, "b": 0, "c": 0})
    assert one.gini == pytest.approx(2 / 3) and one.max_over_mean == pytest.approx(3.0)


def test_balancing_flattens_scenes_and_categories() -> None:
    items = skewed_items()
    selection = select(items, BalanceConfig())
    assert selection.per_scene == 10  # the median scene count
    scenes = Counter(item.scene for item in selection.kept)
    categories = Counter(item.category for item in selection.kept)
    assert max(scenes.values()) <= selection.per_scene
    assert max(categories.values()) <= selection.per_category
    for before, after in (
        (selection.scenes_before, selection.scenes_after),
        (selection.categories_before, selection.categories_after),
    ):
        assert flatness(after).gini < flatness(before).gini - 0.1
        assert flatness(after).max_over_mean < flatness(before).max_over_mean
    # every category is kept: the rare ones are taken before the crowded scenes fill up
    assert set(categories) == set(selection.categories_before)
    assert set(selection.kept) <= set(items)


def test_the_seed_decides_the_selection() -> None:
    """Among equally rare trajectories the seed picks: the same seed, the same set."""
    items = skewed_items()
    first = select(items, BalanceConfig(seed=1, per_scene=3, per_category=50))
    assert select(items, BalanceConfig(seed=1, per_scene=3, per_category=50)) == first
    assert select(items, BalanceConfig(seed=2, per_scene=3, per_category=50)).kept != first.kept
    kept = Counter(item.scene for item in first.kept)
    assert kept == {name: min(3, count) for name, count in first.scenes_before.items()}


def test_the_report_states_the_figures(tmp_path: Path) -> None:
    selection = select(skewed_items(), BalanceConfig())
    md, png = write_report(selection, tmp_path, Path("dataset"))
    text = md.read_text()
    before = flatness(selection.scenes_before).gini
    after = flatness(selection.scenes_after).gini
    assert f"{before:.3f} → {after:.3f}" in text
    assert f"Kept {len(selection.kept)} of {len(skewed_items())} trajectories" in text
    with Image.open(png) as image:
        assert image.size == (1300, 800)
