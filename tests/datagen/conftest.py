"""A small real dataset, built once per test run (by the first worker that asks) and shared,
read only, by the pipeline tests."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import built_once
from vlln.datagen.build import BuildConfig, build_dataset

SMALL = BuildConfig(houses=2, per_house=1, preset="small")


@pytest.fixture(scope="session")
def small_dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return built_once(
        tmp_path_factory, "small_dataset", lambda out: build_dataset(out, SMALL, progress=False)
    )


def dataset_files(root: Path) -> dict[str, bytes]:
    """Every file of a dataset by relative path, with its bytes."""
    return {
        str(path.relative_to(root)): path.read_bytes()
        for path in sorted(root.rglob("*"))
        if path.is_file()
    }
