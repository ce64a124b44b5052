"""The on-disk trajectory dataset: a versioned, LeRobot-style folder per house.

::

    trajectories/<house>/                       e.g. trajectories/house_00003/
      meta/info.json          format version, cameras, columns, generator settings, totals,
                              rejections by reason (written when the house is finished)
      meta/episodes.jsonl     one row per kept trajectory: episode_index, episode_id, tasks,
                              length, dialogs [{role, message, true_idx, nav_idx, ...}], target
      meta/journal.jsonl      every attempt in order, kept or rejected (the resume log)
      data/chunk-000/episode_000000.parquet     one row per frame (see FRAME_COLUMNS)
      images/level_rgb/episode_000000/frame_000000.jpg     the level camera
      images/level_depth/episode_000000/frame_000000.png   its depth, uint16 millimetres
      images/down_rgb/..., images/down_depth/...            the camera tilted 30° down

Frame ``i`` of an episode is what both cameras saw before action ``i``; depth is z-depth along
the optical axis (0 = nothing drawn), as :mod:`vlln.sim.camera` defines it. A dialog row's
``true_idx`` is the frame at which it was asked and ``nav_idx`` the frame whose action acts on
it (the same frame: questions take no frame).

A trajectory's files are written first and its journal line last, so a kill leaves at most
one trajectory's files orphaned, and the restarted build writes them again, identically.
"""

from __future__ import annotations

import io
import json
import os
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from numpy.typing import NDArray
from PIL import Image
from scipy.spatial.transform import Rotation

from vlln.datagen.collector.visibility import DOWN_TILT, DOWN_TILT_DEG
from vlln.datagen.trajectory import Trajectory
from vlln.errors import DataFormatError
from vlln.files import write_text_atomic
from vlln.sim.agent import Action
from vlln.sim.camera import CameraSpec
from vlln.sim.renderer import Frame
from vlln.tasks.episode import scene_name

FORMAT_VERSION = "vlln-trajectories/1.0"
CHUNK_SIZE = 1000
CAMERAS = ("level", "down")
JPEG_QUALITY = 90
FRAME_COLUMNS: dict[str, tuple[str, list[int]]] = {
    "episode_index": ("int64", []),
    "frame_index": ("int64", []),
    "action": ("int64", []),
    "collided": ("bool", []),
    "agent_position": ("float64", [3]),
    "agent_rotation": ("float64", [4]),
    "level_camera_position": ("float64", [3]),
    "level_camera_rotation": ("float64", [4]),
    "down_camera_position": ("float64", [3]),
    "down_camera_rotation": ("float64", [4]),
    "geodesic_distance": ("float64", []),
}


def house_dir_name(scene_id: str) -> str:
    """``vlln/house_00003/house_00003.glb`` -> ``house_00003``: one folder per scene."""
    return scene_name(scene_id.rstrip("/"))


def data_path(episode_index: int) -> str:
    return f"data/chunk-{episode_index // CHUNK_SIZE:03d}/episode_{episode_index:06d}.parquet"


def image_path(camera: str, kind: str, episode_index: int, frame_index: int) -> str:
    """``kind`` is "rgb" (JPEG) or "depth" (16-bit PNG, millimetres)."""
    suffix = "jpg" if kind == "rgb" else "png"
    return f"images/{camera}_{kind}/episode_{episode_index:06d}/frame_{frame_index:06d}.{suffix}"


def camera_rotation(yaw: float, tilt: float) -> list[float]:
    """Quaternion [x, y, z, w] of a camera turned by ``yaw`` and pitched by ``tilt``."""
    quaternion = Rotation.from_euler("YX", [yaw, tilt]).as_quat()
    return [float(v) for v in quaternion]


def depth_to_png(depth: NDArray[np.float32]) -> bytes:
    millimetres = np.clip(np.rint(depth * 1000.0), 0, 65535).astype(np.uint16)
    buffer = io.BytesIO()
    Image.fromarray(millimetres).save(buffer, "PNG", compress_level=1)
    return buffer.getvalue()


def rgb_to_jpeg(rgb: NDArray[np.uint8]) -> bytes:
    buffer = io.BytesIO()
    Image.fromarray(rgb).save(buffer, "JPEG", quality=JPEG_QUALITY)
    return buffer.getvalue()


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
        self.scene_id = scene_id
        self.camera = camera
        self.attempts = read_journal(self.root / "meta" / "journal.jsonl")

    @property
    def finished(self) -> bool:
        return (self.root / "meta" / "info.json").exists()

    @property
    def next_index(self) -> int:
        return sum(1 for a in self.attempts.values() if a.episode_index is not None)

    def write_kept(self, trajectory: Trajectory, frames: Iterable[tuple[Frame, Frame]]) -> int:
        """Images and parquet of a trajectory, then its journal line; returns its index."""
        index = self.next_index
        for frame_index, (level, down) in enumerate(frames):
            for camera, frame in (("level", level), ("down", down)):
                rgb = rgb_to_jpeg(frame.rgb)
                self._write(image_path(camera, "rgb", index, frame_index), rgb)
                depth = depth_to_png(frame.depth)
                self._write(image_path(camera, "depth", index, frame_index), depth)
        self._write(data_path(index), _parquet_bytes(self._frame_table(trajectory, index)))
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
        write_text_atomic(self.root / "meta" / "episodes.jsonl", text)
        rejections: dict[str, int] = {}
        for attempt in self.attempts.values():
            if attempt.reason is not None:
                rejections[attempt.reason] = rejections.get(attempt.reason, 0) + 1
        document = {
            "format_version": FORMAT_VERSION,
            "scene_id": self.scene_id,
            "total_episodes": len(rows),
            "total_frames": sum(int(row["length"]) for row in rows),
            "attempted": len(self.attempts),
            "rejections": dict(sorted(rejections.items())),
            "chunks_size": CHUNK_SIZE,
            "data_path": "data/chunk-{chunk:03d}/episode_{episode_index:06d}.parquet",
            "image_path": "images/{camera}_{kind}/episode_{episode_index:06d}/"
            "frame_{frame_index:06d}.{jpg|png}",
            "cameras": camera_info(self.camera),
            "depth": {"unit": "millimetre", "dtype": "uint16", "zero": "nothing drawn"},
            "actions": {str(int(a)): a.name for a in Action},
            "features": {
                name: {"dtype": dtype, "shape": shape}
                for name, (dtype, shape) in FRAME_COLUMNS.items()
            },
            **info,
        }
        write_text_atomic(self.root / "meta" / "info.json", json.dumps(document, indent=2) + "\n")

    # ----------------------------------------------------------------- internals
    def _write(self, relative: str, data: bytes) -> None:
        path = self.root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)

    def _journal(self, attempt: Attempt) -> None:
        path = self.root / "meta" / "journal.jsonl"
        path.parent.mkdir(parents=True, exist_ok=True)
        line: dict[str, Any] = {
            "episode_id": attempt.episode_id,
            "episode_index": attempt.episode_index,
            "reason": attempt.reason,
            "row": attempt.row,
        }
        with path.open("a", encoding="utf-8") as handle:
            handle.write(json.dumps(line, sort_keys=True) + "\n")
            handle.flush()
            os.fsync(handle.fileno())
        self.attempts[attempt.episode_id] = attempt

    def _frame_table(self, trajectory: Trajectory, index: int) -> pa.Table:
        spec = self.camera
        columns: dict[str, list[Any]] = {name: [] for name in FRAME_COLUMNS}
        for frame_index, step in enumerate(trajectory.steps):
            state = step.state
            eye = [float(v) for v in spec.eye(state.position)]
            columns["episode_index"].append(index)
            columns["frame_index"].append(frame_index)
            columns["action"].append(int(step.action))
            columns["collided"].append(step.collided)
            columns["agent_position"].append([float(v) for v in state.position])
            columns["agent_rotation"].append(camera_rotation(state.yaw, 0.0))
            columns["level_camera_position"].append(eye)
            columns["level_camera_rotation"].append(camera_rotation(state.yaw, 0.0))
            columns["down_camera_position"].append(eye)
            down = camera_rotation(state.yaw, DOWN_TILT)
            columns["down_camera_rotation"].append(down)
            columns["geodesic_distance"].append(float(step.geodesic_distance))
        arrays = {}
        for name, (dtype, shape) in FRAME_COLUMNS.items():
            kind = pa.from_numpy_dtype(np.dtype(dtype))
            arrow_type = pa.list_(kind, shape[0]) if shape else kind
            arrays[name] = pa.array(columns[name], type=arrow_type)
        return pa.table(arrays)


def camera_info(spec: CameraSpec) -> dict[str, Any]:
    common = {"width": spec.width, "height": spec.height, "hfov_deg": spec.hfov_deg}
    common["height_m"] = spec.height_m
    return {
        "level": {**common, "tilt_deg": 0.0},
        "down": {**common, "tilt_deg": DOWN_TILT_DEG},
    }


def episode_row(trajectory: Trajectory, index: int) -> dict[str, Any]:
    """The episodes.jsonl row: the released fields plus the target and what was walked."""
    episode = trajectory.episode
    dialogs: list[dict[str, Any]] = []
    for turn in trajectory.dialog:
        at = {"true_idx": turn.frame_index, "nav_idx": turn.frame_index}
        dialogs.append(
            {"role": "navigator", "message": turn.question, **at, "trigger": turn.trigger}
        )
        dialogs.append(
            {"role": "oracle", "message": turn.answer, **at, "question_type": turn.question_type}
        )
    return {
        "episode_index": index,
        "episode_id": episode.episode_id,
        "scene_id": episode.scene_id,
        "tasks": [episode.instruction.instruction_text],
        "length": trajectory.length,
        "dialogs": dialogs,
        "target": {
            "instance_id": episode.instruction.instance_id[0],
            "category": episode.object_category,
        },
        "path_length": round(trajectory.path_length, 4),
        "geodesic_distance": round(trajectory.steps[0].geodesic_distance, 4),
    }


def _parquet_bytes(table: pa.Table) -> bytes:
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink, compression="zstd")
    return bytes(sink.getvalue().to_pybytes())


def read_journal(path: Path) -> dict[str, Attempt]:
    """Attempts by episode id. A torn last line (a kill mid-write) is cut from the file, so
    that the next attempt starts on a line of its own."""
    attempts: dict[str, Attempt] = {}
    if not path.exists():
        return attempts
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    for number, line in enumerate(lines, 1):
        try:
            data = json.loads(line)
            attempt = Attempt(
                data["episode_id"], data["episode_index"], data["reason"], data["row"]
            )
        except (ValueError, KeyError, TypeError) as error:
            if number < len(lines):
                raise DataFormatError(
                    f"{path}:{number}: unreadable journal line ({error}); the file was edited "
                    "or damaged: delete the house folder to rebuild it"
                ) from error
            write_text_atomic(path, "".join(f"{kept}\n" for kept in lines[:-1]))
            return attempts
        attempts[attempt.episode_id] = attempt
    if text and not text.endswith("\n"):
        write_text_atomic(path, text + "\n")  # a whole last line that lost its newline
    return attempts


# ------------------------------------------------------------------------------- reading
class HouseDataset:
    """A finished house folder: its info, its episodes, their frames and images."""

    def __init__(self, root: str | Path) -> None:
        self.root = Path(root)
        info_path = self.root / "meta" / "info.json"
        if not info_path.exists():
            raise DataFormatError(
                f"{self.root} is not a finished trajectory folder (no meta/info.json); "
                "run or resume `vlln data build` to finish it"
            )
        self.info: dict[str, Any] = json.loads(info_path.read_text(encoding="utf-8"))
        if self.info.get("format_version") != FORMAT_VERSION:
            raise DataFormatError(
                f"{info_path}: format {self.info.get('format_version')!r}, this vlln reads "
                f"{FORMAT_VERSION!r}; rebuild the data with this version"
            )
        lines = (self.root / "meta" / "episodes.jsonl").read_text(encoding="utf-8").splitlines()
        self.episodes: list[dict[str, Any]] = [json.loads(line) for line in lines if line]

    def frames(self, episode_index: int) -> dict[str, NDArray[Any]]:
        """The parquet columns of one episode as arrays (vectors as (n, k) arrays)."""
        table = pq.read_table(self.root / data_path(episode_index))
        out: dict[str, NDArray[Any]] = {}
        for name in table.column_names:
            column = table.column(name).to_pylist()
            out[name] = np.asarray(column)
        return out

    def image_file(self, camera: str, kind: str, episode_index: int, frame_index: int) -> Path:
        return self.root / image_path(camera, kind, episode_index, frame_index)

    def rgb(self, camera: str, episode_index: int, frame_index: int) -> NDArray[np.uint8]:
        with Image.open(self.image_file(camera, "rgb", episode_index, frame_index)) as image:
            return np.asarray(image.convert("RGB"))

    def depth(self, camera: str, episode_index: int, frame_index: int) -> NDArray[np.float32]:
        """Depth in metres."""
        with Image.open(self.image_file(camera, "depth", episode_index, frame_index)) as image:
            return np.asarray(image, dtype=np.float32) / 1000.0


def house_folders(dataset_root: str | Path) -> Iterator[Path]:
    """The house folders under ``<root>/trajectories`` in name order (finished or not)."""
    base = Path(dataset_root) / "trajectories"
    if base.is_dir():
        yield from sorted(p for p in base.iterdir() if p.is_dir())
