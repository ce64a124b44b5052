"""`vlln world export --subdivide N`: a scan-sized test scene from a procedural house."""

from __future__ import annotations

from pathlib import Path

import pytest

from vlln.cli import main
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.scans.gltf import read_glb

SMALL = ["--param", "min_rooms=3", "--param", "max_rooms=4"]


def test_export_splits_every_triangle_into_four_per_step(tmp_path: Path) -> None:
    args = ["world", "export", "--seed", "7", *SMALL, "--out", str(tmp_path), "--style", "mp3d"]
    assert main([*args, "--subdivide", "1"]) == 0
    house = generate_house(7, HouseParameters(min_rooms=3, max_rooms=4))
    assert house.geometry is not None
    triangles, _ = read_glb(tmp_path / "mp3d" / house.name / f"{house.name}.glb")
    assert len(triangles) == 4 * house.geometry.mesh.n_triangles


def test_too_many_steps_are_refused_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["world", "export", "--seed", "7", *SMALL, "--out", str(tmp_path), "--subdivide", "6"]
    assert main(args) == 2
    assert capsys.readouterr().err.strip() == (
        "error: --subdivide 6 is out of range; use 0 to 4 (each step: 4x)"
    )
    assert not any(tmp_path.iterdir())
