"""Fixtures that several test packages share, each built once per session and only read by
the tests that use it."""

from __future__ import annotations

import fcntl
import os
import shutil
from collections.abc import Callable
from pathlib import Path

import pytest

# One thread per process for OpenMP (torch), BLAS and Mesa's rasteriser (llvmpipe): each
# starts one per core by default, and under two pytest-xdist workers (or any other load) those
# threads spin against each other; a torch or rendering test then runs 3 to 4 times slower.
# Set before anything imports them, and inherited by the subprocesses tests start.
for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "LP_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

from vlln.datagen.build import BuildConfig, build_dataset  # noqa: E402


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The files that hold slow tests first, each file's tests together and in order: two
    workers then share the short tests at the end of the run, instead of one waiting while
    the other finishes a long test."""
    slow = {item.nodeid.split("::")[0] for item in items if item.get_closest_marker("slow")}
    items.sort(key=lambda item: item.nodeid.split("::")[0] not in slow)


ONE_HOUSE = BuildConfig(houses=1, per_house=1, preset="small")
"""``vlln data build --houses 1 --per-house 1``: the train split's first house, one trajectory."""


def built_once(
    tmp_path_factory: pytest.TempPathFactory, name: str, build: Callable[[Path], object]
) -> Path:
    """The folder ``name``, built by ``build`` for the whole run: by the first pytest-xdist
    worker that asks (the workers' temporary folders share a parent), the others waiting on a
    lock and then reading it. Its users only read it."""
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent
    folder, done = root / name, root / f"{name}.built"
    with open(root / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not done.exists():
            shutil.rmtree(folder, ignore_errors=True)  # a build that a failure cut short
            folder.mkdir()
            build(folder)
            done.touch()
    return folder


@pytest.fixture(scope="session")
def one_house_dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A real dataset of :data:`ONE_HOUSE` (the training export's source, and what a build on
    Ray must equal)."""
    return built_once(
        tmp_path_factory, "one_house", lambda out: build_dataset(out, ONE_HOUSE, progress=False)
    )


@pytest.fixture(scope="session")
def split_cache(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A cache folder holding the test split's first house (its three tasks' episodes),
    built once for every evaluation, gym and cluster test."""
    from vlln.tasks.split_files import load_or_build_split

    return built_once(
        tmp_path_factory,
        "episodes",
        lambda cache: load_or_build_split("test", "iign", 1, cache, progress=False),
    )


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny Qwen2.5-VL-style model built from a small config."""
    from vlln.train.scratch import build_tiny_model  # the model extra: only where a test asks

    return built_once(tmp_path_factory, "tiny_model", build_tiny_model)
