"""Reading a built trajectory dataset for export, checking what the export relies on."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from vlln.datagen.layout import HouseDataset, house_folders
from vlln.datagen.sft.decisions import check_actions
from vlln.datagen.sft.dialog import DialogExchange
from vlln.errors import ConfigError, DataFormatError
from vlln.sim.camera import CameraSpec


@dataclass(frozen=True)
class SourceTrajectory:
    """One kept trajectory: what the decisions and the prompts need of it."""

    house: str  # folder name, e.g. house_00003
    episode_index: int
    category: str
    actions: list[int]
    feet: NDArray[np.float64]  # (n, 3) agent positions, y = floor
    down_eyes: NDArray[np.float64]  # (n, 3) look-down camera positions
    down_rotations: NDArray[np.float64]  # (n, 4) look-down camera quaternions [x, y, z, w]
    exchanges: tuple[DialogExchange, ...]  # in asking order, as recorded


def open_houses(dataset_root: str | Path) -> list[HouseDataset]:
    """The finished house folders of a dataset, in name order."""
    root = Path(dataset_root)
    if not root.is_dir():
        raise ConfigError(f"{root} is not a folder; give the folder that `vlln data build` wrote")
    folders = list(house_folders(root))
    if not folders:
        raise DataFormatError(
            f"{root} is not a vlln trajectory dataset: it has no trajectories/<house>/ "
            "folders; build one with `vlln data build`"
        )
    return [HouseDataset(folder) for folder in folders]


def down_camera(house: HouseDataset) -> CameraSpec:
    """The intrinsics of the look-down camera recorded in the house's info.json."""
    try:
        down = house.info["cameras"]["down"]
        return CameraSpec(
            width=int(down["width"]),
            height=int(down["height"]),
            hfov_deg=float(down["hfov_deg"]),
            height_m=float(down["height_m"]),
        )
    except (KeyError, TypeError, ValueError, ConfigError) as error:
        raise DataFormatError(
            f"{house.root}/meta/info.json: no usable cameras.down entry ({error}); rebuild "
            "the house with `vlln data build`"
        ) from error


def read_trajectories(house: HouseDataset) -> Iterator[SourceTrajectory]:
    """The house's kept trajectories in episode order."""
    for row in house.episodes:
        where = f"{house.root}/meta/episodes.jsonl, episode {row.get('episode_index')!r}"
        try:
            yield _trajectory(house, row)
        except (KeyError, TypeError, ValueError, OSError) as error:
            if isinstance(error, DataFormatError):
                raise DataFormatError(f"{where}: {error}") from error
            raise DataFormatError(
                f"{where}: unreadable ({error!r}); rebuild the house with `vlln data build`"
            ) from error


def _trajectory(house: HouseDataset, row: dict[str, Any]) -> SourceTrajectory:
    index = int(row["episode_index"])
    frames = house.frames(index)
    actions = [int(a) for a in frames["action"]]
    check_actions(actions)
    if len(actions) != int(row["length"]):
        raise DataFormatError(
            f"{len(actions)} frames in the parquet file, the row says {row['length']}"
        )
    return SourceTrajectory(
        house=house.root.name,
        episode_index=index,
        category=str(row["target"]["category"]),
        actions=actions,
        feet=np.asarray(frames["agent_position"], np.float64),
        down_eyes=np.asarray(frames["down_camera_position"], np.float64),
        down_rotations=np.asarray(frames["down_camera_rotation"], np.float64),
        exchanges=tuple(_exchanges(row["dialogs"])),
    )


def _exchanges(dialogs: list[dict[str, Any]]) -> Iterator[DialogExchange]:
    """Navigator rows, each followed by the oracle row answering it at the same frame."""
    if len(dialogs) % 2:
        raise DataFormatError("dialogs must come in navigator/oracle pairs")
    for question, answer in zip(dialogs[::2], dialogs[1::2], strict=True):
        roles = (question["role"], answer["role"])
        frame = int(question["true_idx"])
        if roles != ("navigator", "oracle") or int(answer["true_idx"]) != frame:
            raise DataFormatError(
                f"dialog rows at frame {frame} are {roles}; expected a navigator question "
                "then the oracle's answer at the same frame"
            )
        yield DialogExchange(frame, str(question["message"]), str(answer["message"]))
