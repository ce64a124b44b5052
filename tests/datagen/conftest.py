"""A small real dataset, built once per test session and shared by the pipeline tests."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.datagen.build import BuildConfig, build_dataset

SMALL = BuildConfig(houses=2, per_house=1, preset="small")


@pytest.fixture(scope="session")
def small_dataset(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return build_dataset(tmp_path_factory.mktemp("dataset"), SMALL, progress=False)


def dataset_files(root: Path) -> dict[str, bytes]:
    """Every file of a dataset by relative path, with its bytes."""
    return {
        str(path.relative_to(root)): path.read_bytes()
        for path in sorted(root.rglob("*"))
        if path.is_file()
    }
