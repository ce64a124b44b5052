"""Reading a built trajectory dataset for export, checking what the export relies on.

Any folder in the reference's layout is accepted (``meta/info.json`` is optional); what the
export takes from an episode is what the reference's training code takes: the instruction,
the actions, the pixel goals of the look-down camera and the dialog turns.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vlln.datagen.layout import EPISODES_FILE, TRAJECTORIES_DIR
from vlln.datagen.reader import HouseDataset, house_folders, instruction_of
from vlln.errors import ConfigError, DataFormatError
from vlln.files import open_image
from vlln.prompt import DOWN_IMAGE_SIZE, DialogExchange


@dataclass(frozen=True)
class SourceTrajectory:
    """One trajectory: what the sampling and the prompt need of it."""

    house: str  # folder name, e.g. house_00003
    episode_index: int
    episode_key: str  # the episode id when recorded, else house/episode_index
    scene_id: str  # as the episode file names it ("" when not recorded)
    instruction: str
    actions: list[int]  # actions[t]: what was done at frame t (the last one: STOP, 0)
    # per frame: (frames ahead, (col, row) on the 640x480 look-down image); -1 and (-1, -1): none
    goals: list[tuple[int, tuple[int, int]]]
    exchanges: tuple[DialogExchange, ...]  # sorted by frame, in asking order within a frame
    target: str = ""  # the target's instance id, as episodes.jsonl records it ("" if not)


def open_houses(dataset_root: str | Path) -> list[HouseDataset]:
    """The house folders of a dataset that hold episodes, in name order."""
    root = Path(dataset_root)
    if not root.is_dir():
        raise ConfigError(f"{root} is not a folder; give the folder that `vlln data build` wrote")
    folders = [f for f in house_folders(root) if (f / EPISODES_FILE).exists()]
    if not folders:
        raise DataFormatError(
            f"{root} is not a trajectory dataset: no {TRAJECTORIES_DIR}/<house>/{EPISODES_FILE}; "
            "build one with `vlln data build`, or finish the build"
        )
    return [HouseDataset(folder) for folder in folders]


def read_trajectories(house: HouseDataset) -> Iterator[SourceTrajectory]:
    """The house's trajectories in episode order."""
    for row in house.episodes:
        where = f"{house.root}/meta/episodes.jsonl, episode {row.get('episode_index')!r}"
        try:
            yield _trajectory(house, row)
        except DataFormatError as error:
            raise DataFormatError(f"{where}: {error}") from error
        except (KeyError, TypeError, ValueError, OSError, IndexError) as error:
            raise DataFormatError(
                f"{where}: unreadable ({error!r}); rebuild the house with `vlln data build`"
            ) from error


def _trajectory(house: HouseDataset, row: dict[str, Any]) -> SourceTrajectory:
    index = int(row["episode_index"])
    frames = house.frames(index)
    stored = [int(a) for a in frames["action"]]
    if len(stored) != int(row["length"]):
        raise DataFormatError(
            f"{len(stored)} frames in the parquet file, the row says {row['length']}"
        )
    down = house.settings["down"]
    relative = [int(r) for r in frames[f"relative_goal_frame_id.{down}"]]
    scale = _goal_scale(house, index)
    target = row.get("target")  # ours: {instance_id, category}; the reference writes none
    pixels = [_scaled(int(g[0]), int(g[1]), scale) for g in frames[f"goal.{down}"]]
    return SourceTrajectory(
        house=house.root.name,
        episode_index=index,
        episode_key=str(row.get("episode_id", f"{house.root.name}/{index}")),
        scene_id=str(row.get("scene_id", "")),
        instruction=instruction_of(row),
        actions=[*stored[1:], 0],  # the reference's reading: action[i] led to frame i
        goals=list(zip(relative, pixels, strict=True)),
        exchanges=tuple(_exchanges(row["dialogs"])),
        target=str(target.get("instance_id", "")) if isinstance(target, dict) else "",
    )


def _goal_scale(house: HouseDataset, index: int) -> tuple[float, float]:
    """From the recorded look-down image's pixels to those of the image the model is shown."""
    path = house.image_file("down", index, 0)
    with open_image(path, path) as image:
        width, height = image.size
    return DOWN_IMAGE_SIZE[0] / width, DOWN_IMAGE_SIZE[1] / height


def _scaled(col: int, row: int, scale: tuple[float, float]) -> tuple[int, int]:
    if col < 0 or scale == (1.0, 1.0):
        return col, row
    width, height = DOWN_IMAGE_SIZE
    return (
        min(width - 1, math.floor((col + 0.5) * scale[0])),
        min(height - 1, math.floor((row + 0.5) * scale[1])),
    )


def _exchanges(dialogs: list[dict[str, Any]]) -> list[DialogExchange]:
    """Navigator rows, each followed by the oracle row answering it, sorted by frame."""
    if len(dialogs) % 2:
        raise DataFormatError("dialogs must come in navigator/oracle pairs")
    exchanges = []
    for question, answer in zip(dialogs[::2], dialogs[1::2], strict=True):
        roles = (question["role"], answer["role"])
        frame = int(question["true_idx"])
        if roles != ("navigator", "oracle") or int(answer["true_idx"]) != frame:
            raise DataFormatError(
                f"dialog rows at frame {frame} are {roles}; expected a navigator question "
                "then the oracle's answer at the same frame"
            )
        exchanges.append(DialogExchange(frame, str(question["message"]), str(answer["message"])))
    return sorted(exchanges, key=lambda exchange: exchange.frame)
