"""A real training export made by the command line, shared by the training and model-agent
tests (the tiny model and the dataset it is exported from: tests/conftest.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.cli import main


@pytest.fixture(scope="session")
def sft_export(one_house_dataset: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``vlln data export-sft`` of the one-house build (one trajectory)."""
    export = tmp_path_factory.mktemp("pipeline") / "export"
    command = ["data", "export-sft", str(one_house_dataset), "--out", str(export), "--quiet"]
    assert main(command) == 0
    return export
