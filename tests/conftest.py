"""Fixtures that several test packages share, each built once per session and only read by
the tests that use it."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.datagen.build import BuildConfig, build_dataset

ONE_HOUSE = BuildConfig(houses=1, per_house=1, preset="small")
"""``vlln data build --houses 1 --per-house 1``: the train split's first house, one trajectory."""


@pytest.fixture(scope="session")
def one_house_dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A real dataset of :data:`ONE_HOUSE` (the training export's source, and what a build on
    Ray must equal)."""
    return build_dataset(tmp_path_factory.mktemp("one_house"), ONE_HOUSE, progress=False)


@pytest.fixture(scope="session")
def split_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A cache folder holding the test split's first house (its three tasks' episodes),
    built once for every evaluation, gym and cluster test."""
    from vlln.tasks.split_files import load_or_build_split

    cache = tmp_path_factory.mktemp("episodes")
    load_or_build_split("test", "iign", 1, cache, progress=False)
    return cache


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny Qwen2.5-VL-style model built from a small config."""
    from vlln.train.scratch import build_tiny_model  # the model extra: only where a test asks

    return build_tiny_model(tmp_path_factory.mktemp("tiny_model"))
