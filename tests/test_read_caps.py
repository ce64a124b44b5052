"""Bounded reads: a gzip bomb, an endless ``--config`` and a file past its cap (an episode or
results file, a model's chat template, Matterport3D files, a recipe's agreement figures) are
one line that names the cap and how to raise it, read no further than the cap; a scan mesh,
a frame table and an image are measured before a library reads them whole."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest
from PIL import Image

from vlln.agents.local.encoding import ChatEncoder
from vlln.bench.mp3d_connectivity import building_graph
from vlln.bench.mp3d_house import house_stats
from vlln.bench.recipe import recipe_figures
from vlln.cli import main
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.results import RESULTS_CAP, scan_records
from vlln.files import ReadCap
from vlln.tasks.episode import EPISODE_FILE_CAP, read_episodes
from vlln.train.data import load_rgb
from vlln.world.scans.gltf import SCAN_MESH_CAP, read_glb


def sparse(path: Path, mib: int) -> Path:
    """A file of ``mib`` MiB and one byte of zeros that takes no disk."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("wb") as handle:
        handle.truncate((mib << 20) + 1)
    return path


def bomb(path: Path, mib: int) -> Path:
    """A gzip file of ``mib`` MiB of spaces, some kilobytes on disk: a valid JSON prefix."""
    path.write_bytes(gzip.compress(b'{"episodes": [' + b" " * (mib << 20), compresslevel=9))
    return path


def test_a_gzip_bomb_stops_at_the_episode_file_cap(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(EPISODE_FILE_CAP.variable or "", "1")
    path = bomb(tmp_path / "val_iign.json.gz", 8)
    assert path.stat().st_size < 50_000
    with pytest.raises(DataFormatError) as info:
        read_episodes(path)
    message = str(info.value)
    assert message == (
        f"{path} holds more than 1 MiB after decompression, the cap on an episode file; "
        "set VLLN_MAX_EPISODE_FILE_MB to more MiB if the file is right"
    )


def test_a_bad_cap_setting_is_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VLLN_MAX_EPISODE_FILE_MB", "lots")
    with pytest.raises(ConfigError, match="VLLN_MAX_EPISODE_FILE_MB='lots': give a whole"):
        read_episodes(bomb(tmp_path / "e.json.gz", 1))


def test_config_from_dev_zero_is_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["eval", "--config", "/dev/zero", "--out", "o"]) == 2
    assert capsys.readouterr().err == (
        "error: --config /dev/zero: /dev/zero holds more than 1 MiB, the cap on a settings "
        "file; give the right file\n"
    )


def test_a_results_file_past_its_cap_is_one_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(RESULTS_CAP.variable or "", "1")
    with pytest.raises(DataFormatError, match="VLLN_MAX_RESULTS_FILE_MB"):
        scan_records(sparse(tmp_path / "episodes.jsonl", 1))


@pytest.mark.parametrize("name", ["chat_template.jinja", "chat_template.json"])
def test_a_chat_template_past_its_cap_is_one_line_before_the_model_loads(
    tmp_path: Path, name: str
) -> None:
    path = sparse(tmp_path / "model" / name, 1)
    with pytest.raises(DataFormatError) as info:
        ChatEncoder.load(path.parent)
    assert str(info.value) == (
        f"{path} holds more than 1 MiB, the cap on a chat template; give the right file"
    )


def test_a_chat_template_that_is_not_text_is_one_line(tmp_path: Path) -> None:
    path = tmp_path / "chat_template.json"
    path.write_text('{"chat_template": 5}')
    with pytest.raises(DataFormatError) as info:
        ChatEncoder.load(tmp_path)
    assert str(info.value) == (
        f"{path} is not a chat template (its chat_template is not text); use a Qwen-VL "
        "instruct checkpoint or one saved by vlln train sft"
    )


def test_a_connectivity_file_past_its_cap_is_one_line(tmp_path: Path) -> None:
    path = sparse(tmp_path / "scan_connectivity.json", 16)
    with pytest.raises(DataFormatError) as info:
        building_graph(path)
    assert str(info.value) == (
        f"{path} holds more than 16 MiB, the cap on a connectivity file; give the right file"
    )


def test_a_house_file_past_its_cap_says_how_to_raise_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("VLLN_MAX_SCAN_ANNOTATION_MB", "1")
    path = sparse(tmp_path / "scan.house", 1)
    with pytest.raises(DataFormatError) as info:
        house_stats(path)
    assert str(info.value) == (
        f"{path} holds more than 1 MiB, the cap on a scan's annotation file; "
        "set VLLN_MAX_SCAN_ANNOTATION_MB to more MiB if the file is right"
    )


def test_an_agreement_file_past_its_cap_is_one_line(tmp_path: Path) -> None:
    (tmp_path / "eval").mkdir()
    path = sparse(tmp_path / "agreement" / "100-train.jsonl", 1)
    with pytest.raises(DataFormatError) as info:
        recipe_figures(tmp_path)
    assert str(info.value) == (
        f"{path} holds more than 1 MiB, the cap on an agreement file; give the right file"
    )


def test_a_scan_mesh_past_its_cap_is_refused_before_the_loader_reads_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(SCAN_MESH_CAP.variable or "", "1")
    path = sparse(tmp_path / "scan.glb", 2)
    with pytest.raises(DataFormatError, match=r"more than 1 MiB, the cap on a scan mesh") as error:
        read_glb(path)
    assert "VLLN_MAX_SCAN_MESH_MB" in str(error.value)


def test_a_table_is_measured_uncompressed(tmp_path: Path) -> None:
    cap = ReadCap("a table", 1)
    small = sparse(tmp_path / "t.parquet", 0)
    cap.check_size(small, 1 << 20)  # at the cap: read
    with pytest.raises(DataFormatError, match=r"more than 1 MiB uncompressed, the cap on a table"):
        cap.check_size(small, (1 << 20) + 1)


def test_an_image_of_too_many_pixels_is_refused_before_it_is_decoded(tmp_path: Path) -> None:
    huge = tmp_path / "frame.png"
    Image.new("1", (5000, 5000)).save(huge)  # a few kB on disk, 75 MB decoded as RGB
    assert huge.stat().st_size < 100_000
    with pytest.raises(DataFormatError, match=r"is a 5000 x 5000 image, more than the"):
        load_rgb(huge)
    broken = tmp_path / "broken.jpg"
    broken.write_bytes(b"\xff\xd8 not a jpeg")
    with pytest.raises(DataFormatError, match=r"broken.jpg is not an image vlln can read"):
        load_rgb(broken)
    Image.new("RGB", (640, 480)).save(tmp_path / "frame.jpg")
    assert load_rgb(tmp_path / "frame.jpg").size == (640, 480)
