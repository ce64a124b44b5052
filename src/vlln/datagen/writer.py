"""Writing one house's trajectory folder (see :mod:`vlln.datagen.layout`), resumably.

A trajectory's files are written first and its journal line last, so a kill leaves at most
one trajectory's files orphaned, and the restarted build writes them again, identically.
``meta/episodes.jsonl`` and ``meta/info.json`` are written when the house is finished; the
presence of ``info.json`` marks it as finished.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vlln.datagen.goals import GoalFinder, WalkCheck
from vlln.datagen.layout import (
    CAMERAS,
    EPISODES_FILE,
    HOUSE_LINES_CAP,
    INFO_FILE,
    JOURNAL_FILE,
    camera_setting,
    data_path,
    episode_row,
    frame_image_path,
    frame_table,
    house_dir_name,
    info_document,
    is_finished,
)
from vlln.datagen.trajectory import Trajectory
from vlln.errors import DataFormatError
from vlln.files import (
    parse_json,
    remove_leftover_temp_files,
    write_bytes_atomic,
    write_text_atomic,
    writing,
)
from vlln.prompt.images import stored_frame
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Frame


@dataclass(frozen=True)
class Attempt:
    """One journal line: an episode tried, and either its episode_index or why it was dropped."""

    episode_id: str
    episode_index: int | None
    reason: str | None
    row: dict[str, Any] | None  # the episodes.jsonl row of a kept trajectory


class HouseWriter:
    """Writes one house's trajectories; picks up where a killed build stopped."""

    def __init__(self, root: Path, scene_id: str, camera: CameraSpec) -> None:
        self.root = Path(root) / house_dir_name(scene_id)
        remove_leftover_temp_files(self.root)  # a killed build's; each house has one writer
        self.scene_id = scene_id
        self.camera = camera
        self.attempts = read_journal(self.root / JOURNAL_FILE)

    @property
    def finished(self) -> bool:
        return is_finished(self.root)

    @property
    def next_index(self) -> int:
        return sum(1 for a in self.attempts.values() if a.episode_index is not None)

    def write_kept(
        self,
        trajectory: Trajectory,
        level: Sequence[bytes],
        down: Iterable[Frame],
        walks: WalkCheck | None = None,
    ) -> int:
        """Images and parquet of a trajectory, then its journal line; returns its index.
        ``level`` holds every step's level view as stored (:func:`stored_frame`), ``down``
        its look-down views, whose depth places the pixel goals, and ``walks`` checks that
        the follower walks each goal as the teacher did (:class:`GoalFinder`)."""
        index = self.next_index
        level_setting, down_setting = (camera_setting(self.camera, camera) for camera in CAMERAS)
        finder = GoalFinder(self.camera, trajectory, walks)
        goals = []
        for frame_index, (level_jpeg, down_frame) in enumerate(zip(level, down, strict=True)):
            self._write(frame_image_path(level_setting, index, frame_index), level_jpeg)
            self._write(
                frame_image_path(down_setting, index, frame_index), stored_frame(down_frame.rgb)
            )
            goals.append(finder.at(frame_index, down_frame))
        self._write(data_path(index), frame_table(self.camera, trajectory, index, goals))
        row = episode_row(trajectory, index)
        self._journal(Attempt(trajectory.episode.episode_id, index, None, row))
        return index

    def write_rejected(self, episode_id: str, reason: str) -> None:
        self._journal(Attempt(episode_id, None, reason, None))

    def finish(self, info: dict[str, Any]) -> None:
        """episodes.jsonl, then info.json (its presence marks the house as finished)."""
        rows = [a.row for a in self.attempts.values() if a.row is not None]
        rows.sort(key=lambda row: int(row["episode_index"]))
        text = "".join(json.dumps(row, sort_keys=True) + "\n" for row in rows)
        write_text_atomic(self.root / EPISODES_FILE, text)
        rejections: dict[str, int] = {}
        for attempt in self.attempts.values():
            if attempt.reason is not None:
                rejections[attempt.reason] = rejections.get(attempt.reason, 0) + 1
        document = {
            **info_document(self.camera),
            "scene_id": self.scene_id,
            "total_episodes": len(rows),
            "total_frames": sum(int(row["length"]) for row in rows),
            "attempted": len(self.attempts),
            "rejections": dict(sorted(rejections.items())),
            **info,
        }
        write_text_atomic(self.root / INFO_FILE, json.dumps(document, indent=2) + "\n")

    # ----------------------------------------------------------------- internals
    def _write(self, relative: str, data: bytes) -> None:
        path = self.root / relative
        with writing(path):  # a rerun writes the trajectory again, as after a kill
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)

    def _journal(self, attempt: Attempt) -> None:
        path = self.root / JOURNAL_FILE
        line: dict[str, Any] = {
            "episode_id": attempt.episode_id,
            "episode_index": attempt.episode_index,
            "reason": attempt.reason,
            "row": attempt.row,
        }
        # a line cut short by a full disk is a torn last line, which the rerun cuts
        with writing(path):
            path.parent.mkdir(parents=True, exist_ok=True)
            with path.open("a", encoding="utf-8") as handle:
                handle.write(json.dumps(line, sort_keys=True) + "\n")
                handle.flush()
                os.fsync(handle.fileno())
        self.attempts[attempt.episode_id] = attempt


def read_journal(path: Path) -> dict[str, Attempt]:
    """Attempts by episode id. A torn last line (a kill mid-write) is cut from the file, so
    that the next attempt starts on a line of its own."""
    attempts: dict[str, Attempt] = {}
    if not path.exists():
        return attempts
    text = HOUSE_LINES_CAP.read(path)
    lines = text.splitlines()
    for number, line in enumerate(lines, 1):
        try:
            data = parse_json(line)
            attempt = Attempt(
                data["episode_id"], data["episode_index"], data["reason"], data["row"]
            )
        except (ValueError, KeyError, TypeError) as error:
            if number < len(lines):
                raise DataFormatError(
                    f"{path}:{number}: unreadable journal line ({error}); the file was edited "
                    "or damaged: delete the house folder to rebuild it"
                ) from error
            write_bytes_atomic(path, b"".join(kept + b"\n" for kept in lines[:-1]))
            return attempts
        attempts[attempt.episode_id] = attempt
    if text and not text.endswith(b"\n"):
        write_bytes_atomic(path, text + b"\n")  # a whole last line that lost its newline
    return attempts
