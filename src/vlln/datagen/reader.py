"""Reading a house's trajectory folder: ours, or one in the reference's layout.

``meta/info.json`` is optional, as for the reference's readers: without it the cameras are
the reference's (``125cm_0deg`` and ``125cm_30deg``). With it, its format version must be the
one this vlln writes.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow.parquet as pq
from numpy.typing import NDArray

from vlln.datagen.layout import (
    CAMERAS,
    EPISODES_FILE,
    FORMAT_VERSION,
    HOUSE_LINES_CAP,
    INFO_CAP,
    INFO_FILE,
    TRAJECTORIES_DIR,
    camera_setting,
    data_path,
    frame_image_path,
)
from vlln.errors import DataFormatError
from vlln.files import ReadCap, open_image, parse_json
from vlln.sim.camera import CameraSpec

# An episode's frame table is a few kB (a pose and an action per frame); read whole.
FRAME_TABLE_CAP = ReadCap("an episode's frame table", 64)


class HouseDataset:
    """A house folder: its info (if any), its episodes, their frames and images."""

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root)
        info_path = self.root / INFO_FILE
        self.info: dict[str, Any] = {}
        self.settings = {camera: camera_setting(CameraSpec(), camera) for camera in CAMERAS}
        if info_path.exists():
            self.info = _parse(info_path, INFO_CAP.read(info_path))
            if not isinstance(self.info, dict):
                raise DataFormatError(f"{info_path}: expected a JSON object")
            if self.info.get("format_version") != FORMAT_VERSION:
                raise DataFormatError(
                    f"{info_path}: format {self.info.get('format_version')!r}, this vlln reads "
                    f"{FORMAT_VERSION!r}; rebuild the data with this version"
                )
            self.settings = _settings(self.info, info_path)
        episodes_path = self.root / EPISODES_FILE
        if not episodes_path.exists():
            raise DataFormatError(
                f"{self.root} is not a finished trajectory folder (no {EPISODES_FILE}); "
                "run or resume `vlln data build` to finish it"
            )
        lines = HOUSE_LINES_CAP.read(episodes_path).splitlines()
        self.episodes: list[dict[str, Any]] = [
            _parse(episodes_path, line, number)
            for number, line in enumerate(lines, 1)
            if line.strip()
        ]

    def frames(self, episode_index: int) -> dict[str, NDArray[Any]]:
        """The parquet columns of one episode as arrays (a 4x4 pose per frame: (n, 4, 4))."""
        path = self.root / data_path(episode_index)
        metadata = pq.ParquetFile(path).metadata
        sizes = (metadata.row_group(i).total_byte_size for i in range(metadata.num_row_groups))
        FRAME_TABLE_CAP.check_size(path, sum(sizes))
        table = pq.read_table(path)
        return {name: np.asarray(table.column(name).to_pylist()) for name in table.column_names}

    def image_file(self, camera: str, episode_index: int, frame_index: int) -> Path:
        """``camera`` is "level" or "down"."""
        return self.root / frame_image_path(self.settings[camera], episode_index, frame_index)

    def rgb(self, camera: str, episode_index: int, frame_index: int) -> NDArray[np.uint8]:
        path = self.image_file(camera, episode_index, frame_index)
        with open_image(path, path) as image:
            return np.asarray(image.convert("RGB"))


def _parse(path: Path, data: bytes, line: int | None = None) -> Any:
    try:
        return parse_json(data)
    except DataFormatError as error:
        where = path if line is None else f"{path}:{line}"
        raise DataFormatError(
            f"{where}: {error}; rebuild the house (delete its folder, then `vlln data build`)"
        ) from None


def instruction_of(row: dict[str, Any]) -> str:
    """The instruction of an episodes.jsonl row, as the reference reads it."""
    return str(row["tasks"][0]).split(";")[0]


def _settings(info: dict[str, Any], info_path: Path) -> dict[str, str]:
    """Camera -> setting name, from the pitches recorded in info.json."""
    try:
        by_pitch = {float(c["pitch_deg"]): name for name, c in info["cameras"].items()}
        return {"level": by_pitch[0.0], "down": next(n for p, n in by_pitch.items() if p > 0)}
    except (KeyError, TypeError, ValueError, StopIteration) as error:
        raise DataFormatError(
            f"{info_path}: no usable cameras entry ({error!r}); rebuild the house"
        ) from error


def house_folders(dataset_root: str | Path) -> Iterator[Path]:
    """The house folders under ``<root>/trajectories`` in name order (finished or not)."""
    base = Path(dataset_root) / TRAJECTORIES_DIR
    if base.is_dir():
        yield from sorted(p for p in base.iterdir() if p.is_dir())
