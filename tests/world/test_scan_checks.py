"""Damaged scan annotations: `vlln world import` on a binary, cut or empty `.house`, a binary or
empty HM3D `semantic.txt`, or a scan without rooms says so in one line naming the file."""

from __future__ import annotations

import json
import random
import shutil
import struct
from pathlib import Path

import pytest

from vlln.cli import main
from vlln.world.generator import HouseParameters, generate_house
from vlln.world.scans import export_scene

SMALL = HouseParameters(min_rooms=3, max_rooms=4, min_area=35.0, max_area=55.0)


@pytest.fixture(scope="module")
def exported(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    house = generate_house(7, SMALL)
    root = tmp_path_factory.mktemp("scans")
    return {style: export_scene(house, root / style, style) for style in ("mp3d", "hm3d")}


def damaged(source: Path, to: Path, suffix: str, content: bytes) -> Path:
    """A copy of the scene ``source`` named ``s`` whose ``s<suffix>`` file holds ``content``."""
    scene = to / "s"
    scene.mkdir(parents=True)
    for path in source.iterdir():
        shutil.copy(path, scene / path.name.replace(source.name, "s"))
    (scene / f"s{suffix}").write_bytes(content)
    return scene


def house_text(exported: dict[str, Path]) -> str:
    folder = exported["mp3d"]
    return (folder / f"{folder.name}.house").read_text(encoding="utf-8")


def noise(size: int) -> bytes:
    return random.Random(5).randbytes(size)


def cut_at_line(text: str, kind: str) -> bytes:
    """The file cut cleanly after its first ``kind`` record: whole lines, fewer of them."""
    lines = text.splitlines(keepends=True)
    first = next(i for i, line in enumerate(lines) if line.startswith(f"{kind} "))
    return "".join(lines[: first + 1]).encode()


def roomless(text: str) -> bytes:
    """The header and categories only: a well-formed file that counts no regions."""
    lines = text.splitlines()
    header = lines[1].split()
    header[5] = header[6] = header[10] = header[8] = "0"
    kept = [line for line in lines[2:] if line.startswith("C ")]
    return "\n".join([lines[0], " ".join(header), *kept, ""]).encode()


def with_field(text: str, kind: str, index: int, value: str) -> bytes:
    """The file with field ``index`` of its first ``kind`` record replaced by ``value``."""
    lines = text.splitlines(keepends=True)
    first = next(i for i, line in enumerate(lines) if line.startswith(f"{kind} "))
    fields = lines[first].split()
    fields[index] = value
    lines[first] = " ".join(fields) + "\n"
    return "".join(lines).encode()


def glb(document: str, binary: bytes = b"") -> bytes:
    """A binary glTF as Khronos's glTF 2.0 specification lays it out: a 12-byte header (magic,
    version 2, total length), a JSON chunk padded with spaces, an optional BIN chunk padded
    with zeros, each chunk led by its length and type."""
    chunk = document.encode() + b" " * (-len(document) % 4)
    body = struct.pack("<I4s", len(chunk), b"JSON") + chunk
    if binary:
        binary += b"\0" * (-len(binary) % 4)
        body += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def triangle(*coordinates: float) -> bytes:
    """A .glb of one triangle: its nine float32 coordinates in the BIN chunk, one accessor."""
    document = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36}],
    }
    return glb(json.dumps(document), struct.pack("<9f", *coordinates))


DEEP = "[" * 100_000 + "]" * 100_000
CASES = {
    "binary .house": ("mp3d", ".house", lambda t: noise(3000), "is a binary file"),
    "latin-1 .house": (
        "mp3d",
        ".house",
        lambda t: "ASCII 1.1\nH caf\xe9".encode("latin-1"),
        "UTF-8",
    ),
    "empty .house": ("mp3d", ".house", lambda t: b"", "is empty"),
    "foreign .house": ("mp3d", ".house", lambda t: b"hello\n", "ASCII 1.1"),
    "cut mid-record": ("mp3d", ".house", lambda t: t.encode()[: len(t) // 2], "fields, not"),
    "cut between records": ("mp3d", ".house", lambda t: cut_at_line(t, "V"), "cut short"),
    "roomless .house": ("mp3d", ".house", roomless, "no regions"),
    "5000-digit id in a .house": (
        "mp3d",
        ".house",
        lambda t: with_field(t, "O", 1, "9" * 5000),
        "not a finite number",
    ),
    "NaN coordinate in a .house": (
        "mp3d",
        ".house",
        lambda t: with_field(t, "V", 4, "nan"),
        "not a finite number",
    ),
    "glb JSON nested 100,000 deep": (
        "mp3d",
        ".glb",
        lambda t: glb('{"asset": {"version": "2.0"}, "extras": ' + DEEP + "}"),
        "nested deeper",
    ),
    "5000-digit integer in a glb": (
        "hm3d",
        ".glb",
        lambda t: glb('{"asset": {"version": "2.0"}, "scene": ' + "9" * 5000 + "}"),
        "5000 digits",
    ),
    "glb JSON chunk past its cap": (
        "mp3d",
        ".glb",
        lambda t: struct.pack("<4sIII4s", b"glTF", 2, 1 << 30, 1 << 30, b"JSON"),
        "over the cap",
    ),
    "NaN vertex in a glb": (
        "mp3d",
        ".glb",
        lambda t: triangle(0, 0, 0, 1, float("nan"), 0, 0, 1, 0),
        "not finite",
    ),
    "binary semantic.txt": ("hm3d", ".semantic.txt", lambda t: noise(2000), "binary file"),
    "empty semantic.txt": ("hm3d", ".semantic.txt", lambda t: b"", "lists no objects"),
    "semantic.txt without floors": (
        "hm3d",
        ".semantic.txt",
        lambda t: b'HM3D Semantic Annotations\n1,00FF00,"chair",0\n',
        "yields no rooms",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_damaged_scan_is_one_line(
    exported: dict[str, Path],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    case: str,
) -> None:
    style, suffix, make, reason = CASES[case]
    scene = damaged(exported[style], tmp_path, suffix, make(house_text(exported)))
    assert main(["world", "import", str(scene)]) == 2
    error = capsys.readouterr().err
    assert error.startswith(f"error: {scene}") and error.count("\n") == 1
    assert reason in error, error


def test_the_exported_scans_still_import(
    exported: dict[str, Path], capsys: pytest.CaptureFixture[str]
) -> None:
    for folder in exported.values():
        assert main(["world", "import", str(folder)]) == 0
        assert '"rooms": 0' not in capsys.readouterr().out
