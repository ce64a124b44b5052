"""`vlln world show` writes pictures a person can look at, and bad input gets one clear line."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from vlln.cli import main
from vlln.errors import UnknownCategoryError
from vlln.world.catalogue import default_catalogue


@pytest.mark.slow
def test_world_show_writes_a_map_and_views(tmp_path: Path) -> None:
    out = tmp_path / "show"
    args = ["world", "show", "--seed", "4", "--out", str(out), "--views", "1"]
    assert main([*args, "--param", "max_rooms=5", "--param", "max_area=90"]) == 0
    assert (out / "map.png").stat().st_size > 10_000
    rgb = sorted(out.glob("view0_*_level_rgb.png"))
    ids = sorted(out.glob("view0_*_level_ids.png"))
    assert len(rgb) == 1 and len(ids) == 1
    image = np.asarray(Image.open(rgb[0]))
    assert image.shape == (480, 640, 3)
    assert image.std() > 10  # a textured, lit room, not a blank frame
    assert len(np.unique(np.asarray(Image.open(ids[0])).reshape(-1, 3), axis=0)) > 3


def test_impossible_house_parameters_give_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(
        ["world", "show", "--out", "unused", "--param", "min_rooms=12", "--param", "max_area=60"]
    )
    assert code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: min_rooms=12") and "max_area" in err
    assert "Traceback" not in err


def test_unknown_parameter_lists_the_valid_names(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["world", "show", "--out", "unused", "--param", "rooms=3"]) == 2
    assert "min_rooms, max_rooms" in capsys.readouterr().err


def test_unknown_category_names_the_valid_ones() -> None:
    with pytest.raises(UnknownCategoryError) as error:
        default_catalogue().get("unicorn")
    assert "'unicorn'" in str(error.value) and "chair" in str(error.value)


@pytest.mark.slow
def test_no_egl_gives_the_install_hint(tmp_path: Path) -> None:
    env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES=str(tmp_path / "none.json"))
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "vlln.cli",
            "world",
            "show",
            "--seed",
            "1",
            "--out",
            str(tmp_path / "out"),
            "--param",
            "max_rooms=4",
            "--param",
            "max_area=60",
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 2
    assert "apt-get install libegl1 libgl1-mesa-dri" in result.stderr
    assert "Traceback" not in result.stderr


@pytest.mark.slow
def test_world_show_replaces_its_output_folder(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 8: a second run leaves no file of the first one behind."""
    out = tmp_path / "show"
    args = ["world", "show", "--out", str(out), "--param", "max_rooms=4", "--param", "max_area=70"]
    assert main([*args, "--seed", "1", "--views", "1"]) == 0
    assert len(list(out.glob("view0_*.png"))) == 6
    assert main([*args, "--seed", "2", "--views", "0"]) == 0
    assert sorted(path.name for path in out.iterdir()) == ["map.png"]
    assert not [path for path in tmp_path.iterdir() if path.name != "show"]  # no temp left


def test_world_show_out_of_the_wrong_kind_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Reproduction 10: --out naming a file, or a folder holding other files."""
    file = tmp_path / "notes.txt"
    file.write_text("mine")
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "thesis.tex").write_text("mine")
    for out in (file, tmp_path / "mine"):
        assert main(["world", "show", "--out", str(out), "--views", "0"]) == 2
        error = capsys.readouterr().err
        assert error.startswith("error: ") and error.count("\n") == 1 and str(out) in error
    assert file.read_text() == "mine" and (tmp_path / "mine" / "thesis.tex").exists()
