"""Writing a balanced dataset: the same layout as a build, holding only the kept trajectories.

A separate command rather than a build step, because the caps compare every scene and category
of the finished dataset: a house-by-house build (sharded, resumed, on a cluster) never sees
them all, and a build kept whole can be balanced again with other caps. The kept trajectories
keep their episode indices, and their files are hard links to the source's (copies where the
file system has none), so a balanced dataset costs little disk and ``export-sft`` reads it as
any other. ``build.json`` is the source's plus the ``balance`` settings and caps (so
``vlln data build`` refuses to resume into it), and ``balance/`` holds the report. The
dataset is written in a hidden folder beside ``out`` and renamed into place when complete.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from tqdm import tqdm

from vlln.datagen.balance.report import write_report
from vlln.datagen.balance.select import BalanceConfig, Item, Selection, select
from vlln.datagen.layout import (
    CAMERAS,
    EPISODES_DIR,
    EPISODES_FILE,
    INFO_FILE,
    SCENE_SUMMARY_DIR,
    SETTINGS_CAP,
    SETTINGS_FILE,
    TRAJECTORIES_DIR,
    data_path,
    frame_image_path,
    is_finished,
)
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.errors import ConfigError, DataFormatError
from vlln.files import parse_json, write_text_atomic, writing

REPORT_DIR = "balance"


@dataclass(frozen=True)
class BalanceResult:
    out: Path
    selection: Selection
    report: list[Path]  # the report's files, under ``out``


def balance_dataset(
    dataset: str | Path, out: str | Path, config: BalanceConfig, progress: bool = True
) -> BalanceResult:
    """Write the balanced copy of the finished houses of ``dataset`` to ``out`` (new)."""
    source, target = Path(dataset), Path(out)
    houses = _finished_houses(source)
    if target.exists() and (not target.is_dir() or any(target.iterdir())):
        raise ConfigError(f"{target} exists and is not an empty folder; choose a new --out")
    if target.resolve().is_relative_to(source.resolve()):
        raise ConfigError(f"--out {target} is inside the dataset {source}; choose another folder")
    items = [_item(house, row) for house in houses for row in house.episodes]
    selection = select(items, config)
    with writing(target):  # a failure removes the staging folder: a rerun starts afresh
        target.parent.mkdir(parents=True, exist_ok=True)
        staging = Path(tempfile.mkdtemp(dir=target.parent, prefix=f".{target.name}."))
        try:
            for name in (SCENE_SUMMARY_DIR, EPISODES_DIR):
                if (source / name).is_dir():
                    shutil.copytree(source / name, staging / name, copy_function=_link)
            kept: dict[str, set[int]] = {}
            for item in selection.kept:
                kept.setdefault(item.house, set()).add(item.episode_index)
            for house in tqdm(houses, desc="balance", unit="house", disable=not progress):
                _write_house(house, kept.get(house.root.name, set()), staging)
            write_text_atomic(staging / SETTINGS_FILE, _settings(source, config, selection))
            report = write_report(selection, staging / REPORT_DIR, source)
            if target.exists():
                target.rmdir()
            os.replace(staging, target)
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
    return BalanceResult(target, selection, [target / p.relative_to(staging) for p in report])


def _finished_houses(root: Path) -> list[HouseDataset]:
    if not root.is_dir():
        raise ConfigError(f"{root} is not a folder; give the folder that `vlln data build` wrote")
    houses = [HouseDataset(folder) for folder in house_folders(root) if is_finished(folder)]
    if not sum(len(house.episodes) for house in houses):
        raise DataFormatError(
            f"{root} has no finished house with trajectories; build or finish it with "
            "`vlln data build` first"
        )
    return houses


def _item(house: HouseDataset, row: dict[str, Any]) -> Item:
    try:
        category = str(row["target"]["category"])
        return Item(house.root.name, int(row["episode_index"]), house.root.name, category)
    except (KeyError, TypeError, ValueError) as error:
        raise DataFormatError(
            f"{house.root}/{EPISODES_FILE}: a row without episode_index or target category "
            f"({error!r}); rebuild the house with `vlln data build`"
        ) from error


def _write_house(house: HouseDataset, kept: set[int], out: Path) -> None:
    """The house's kept trajectories (linked), its episode rows and info (totals updated)."""
    folder = out / TRAJECTORIES_DIR / house.root.name
    rows = [row for row in house.episodes if int(row["episode_index"]) in kept]
    for row in rows:
        index = int(row["episode_index"])
        files = [data_path(index)] + [
            frame_image_path(house.settings[camera], index, frame)
            for camera in CAMERAS
            for frame in range(int(row["length"]))
        ]
        for name in files:
            (folder / name).parent.mkdir(parents=True, exist_ok=True)
            _link(house.root / name, folder / name)
    text = "".join(json.dumps(row, sort_keys=True) + "\n" for row in rows)
    write_text_atomic(folder / EPISODES_FILE, text)
    info = dict(house.info)
    info["total_episodes"] = len(rows)
    info["total_frames"] = sum(int(row["length"]) for row in rows)
    info["balanced_from"] = len(house.episodes)
    write_text_atomic(folder / INFO_FILE, json.dumps(info, indent=2) + "\n")


def _settings(source: Path, config: BalanceConfig, selection: Selection) -> str:
    path = source / SETTINGS_FILE
    recorded: dict[str, Any] = {}
    if path.exists():
        data = SETTINGS_CAP.read(path)
        try:
            recorded = parse_json(data)
        except DataFormatError as error:
            raise DataFormatError(f"{path}: {error}") from None
        if not isinstance(recorded, dict):
            raise DataFormatError(f"{path} is not a JSON object of settings")
    recorded["balance"] = {
        **config.to_json(),
        "caps": {"scene": selection.per_scene, "category": selection.per_category},
        "kept": len(selection.kept),
        "of": sum(selection.scenes_before.values()),
    }
    return json.dumps(recorded, indent=2) + "\n"


def _link(src: str | os.PathLike[str], dst: str | os.PathLike[str]) -> None:
    """A hard link, or a copy where the file system cannot link across."""
    try:
        os.link(src, dst)
    except OSError:
        shutil.copy2(src, dst)
