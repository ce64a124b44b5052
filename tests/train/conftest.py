"""A tiny Qwen2.5-VL-style model built from a small config, and a real training export made
by the command line, shared by the training and model-agent tests."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.cli import main
from vlln.train.tiny import build_tiny_model


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return build_tiny_model(tmp_path_factory.mktemp("tiny_model"))


@pytest.fixture(scope="session")
def sft_export(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``vlln data build`` (one house, one trajectory) then ``vlln data export-sft``."""
    root = tmp_path_factory.mktemp("pipeline")
    dataset, export = root / "dataset", root / "export"
    build = ["data", "build", "--houses", "1", "--per-house", "1", "--out", str(dataset)]
    assert main([*build, "--quiet"]) == 0
    assert main(["data", "export-sft", str(dataset), "--out", str(export), "--quiet"]) == 0
    return export
