"""The trajectory folder's pieces: the resume journal and the camera poses it records."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from vlln.datagen.layout import camera_rotation, read_journal
from vlln.errors import DataFormatError
from vlln.sim.camera import CameraSpec


def _line(episode_id: str, index: int | None) -> str:
    row = {"episode_id": episode_id, "episode_index": index, "reason": None, "row": None}
    return json.dumps(row)


def test_a_torn_last_line_is_cut_and_the_rest_kept(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text(_line("a", 0) + "\n" + _line("b", 1) + "\n" + '{"episode_id": "c", "epi')
    attempts = read_journal(journal)
    assert list(attempts) == ["a", "b"]
    assert journal.read_text() == _line("a", 0) + "\n" + _line("b", 1) + "\n"


def test_a_whole_last_line_without_newline_is_kept(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text(_line("a", 0) + "\n" + _line("b", None))
    assert list(read_journal(journal)) == ["a", "b"]
    assert journal.read_text().endswith("\n")


def test_damage_before_the_last_line_is_an_error(tmp_path: Path) -> None:
    journal = tmp_path / "journal.jsonl"
    journal.write_text("not json\n" + _line("b", 0) + "\n")
    with pytest.raises(DataFormatError, match=r"journal\.jsonl:1"):
        read_journal(journal)


@pytest.mark.parametrize("yaw", [0.0, 0.7, -2.5])
@pytest.mark.parametrize("tilt", [0.0, math.radians(-30.0)])
def test_recorded_rotation_is_the_rendering_camera_pose(yaw: float, tilt: float) -> None:
    pose = CameraSpec().camera_to_world((1.0, 0.0, 2.0), yaw, tilt)
    matrix = Rotation.from_quat(camera_rotation(yaw, tilt)).as_matrix()
    assert np.allclose(matrix, pose[:3, :3], atol=1e-12)
