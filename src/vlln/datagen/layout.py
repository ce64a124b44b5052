"""The on-disk trajectory dataset: one LeRobot-style folder per house, in the reference layout.
Every reader and writer of a dataset takes its names and paths from here.

::

    <root>/build.json                           the build's settings (vlln.datagen.build)
    <root>/scene_summary/<house>/               object_dict.json, region_dict.json
    <root>/episodes/<split>_*.json.gz           the split's episodes
    trajectories/<house>/                       e.g. trajectories/house_00003/
      meta/info.json          format version, cameras, columns, pose convention, generator
                              settings, totals, rejections by reason (written last)
      meta/episodes.jsonl     one row per kept trajectory: episode_index, tasks [instruction],
                              length, dialogs [{role, message, true_idx, nav_idx, ...}], and
                              our extras (path_node_to_frame, episode_id, target, ...)
      meta/journal.jsonl      every attempt in order, kept or rejected (the resume log)
      data/chunk-000/episode_000000.parquet     one row per frame (see :func:`frame_columns`)
      videos/chunk-000/observation.images.rgb.125cm_0deg/episode_000000_<frame>.jpg
      videos/chunk-000/observation.images.rgb.125cm_30deg/episode_000000_<frame>.jpg

The names follow the reference's readers: a camera "setting" is its height and pitch
(``125cm_0deg`` level, ``125cm_30deg`` tilted 30° down). ``action[i]`` is the action that led
to frame ``i`` (``action[0]`` is the placeholder -1; the STOP at the last frame is implied).
``pose.<setting>`` is the 4x4 camera-to-world matrix with OpenCV camera axes (x right, y
down, z forward) in a z-up world: world ``(x, y, z)`` = habitat ``(x, -z, y)``.
``goal.125cm_30deg`` is the pixel ``[col, row]`` of the frame's look-down image under which
the agent stands ``relative_goal_frame_id.125cm_30deg`` frames later (``[-1, -1]`` and -1 where
the frame has no pixel goal; see :mod:`vlln.datagen.goals`). Frames are JPEG, stored by
:func:`vlln.prompt.images.stored_frame` (the contract the export and the model agents share);
depth is only used during the build and not stored.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
from numpy.typing import NDArray

from vlln.datagen.collector.visibility import DOWN_TILT_DEG
from vlln.datagen.goals import Goal
from vlln.datagen.trajectory import Trajectory
from vlln.files import ReadCap
from vlln.sim.agent import Action, AgentState
from vlln.sim.camera import CameraSpec, Position
from vlln.tasks.episode import scene_name

FORMAT_VERSION = "vlln-trajectories/2.0"
SETTINGS_FILE = "build.json"
SCENE_SUMMARY_DIR = "scene_summary"
EPISODES_DIR = "episodes"
TRAJECTORIES_DIR = "trajectories"
# In a house folder:
INFO_FILE = "meta/info.json"  # written last: its presence marks a finished house
EPISODES_FILE = "meta/episodes.jsonl"
JOURNAL_FILE = "meta/journal.jsonl"
LAST_FILES = (JOURNAL_FILE, INFO_FILE)  # written after every other file of a house, in order
# The caps on reading them back: build.json and info.json are a few kB; a line of episodes.jsonl
# or of the journal is about 1 kB, so 64 MiB is some 80,000 episodes of one house.
SETTINGS_CAP = ReadCap("a build.json", 1)
INFO_CAP = ReadCap("a house's info.json", 1)
HOUSE_LINES_CAP = ReadCap("a house's episodes.jsonl or journal", 64)
CHUNK_SIZE = 1000
NO_ACTION = -1  # action[0]: no action led to the first frame
CAMERAS = ("level", "down")
_PITCH_DEG = {"level": 0.0, "down": -DOWN_TILT_DEG}

# Habitat world (y up, -z ahead at yaw 0) to the z-up world of the poses, and OpenCV camera
# axes to the renderer's OpenGL ones (y up, looking along -z).
_HABITAT_TO_Z_UP = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
_OPENCV_TO_OPENGL = np.diag([1.0, -1.0, -1.0])


def house_dir_name(scene_id: str) -> str:
    """``vlln/house_00003/house_00003.glb`` -> ``house_00003``: one folder per scene."""
    return scene_name(scene_id.rstrip("/"))


def house_dir(dataset_root: str | Path, scene_id: str) -> Path:
    """The trajectory folder of a scene in a dataset."""
    return Path(dataset_root) / TRAJECTORIES_DIR / house_dir_name(scene_id)


def is_finished(house_folder: Path) -> bool:
    """Whether a house folder is complete (its ``meta/info.json`` is written)."""
    return (house_folder / INFO_FILE).exists()


def camera_setting(spec: CameraSpec, camera: str) -> str:
    """The reference's name of a camera: height and downward pitch, e.g. ``125cm_30deg``."""
    pitch = _PITCH_DEG[camera]
    return f"{round(spec.height_m * 100)}cm_{round(pitch)}deg"


def data_path(episode_index: int) -> str:
    return f"data/chunk-{episode_index // CHUNK_SIZE:03d}/episode_{episode_index:06d}.parquet"


def frame_image_path(setting: str, episode_index: int, frame_index: int) -> str:
    """``videos/chunk-000/observation.images.rgb.125cm_0deg/episode_000000_7.jpg``."""
    chunk = episode_index // CHUNK_SIZE
    folder = f"videos/chunk-{chunk:03d}/observation.images.rgb.{setting}"
    return f"{folder}/episode_{episode_index:06d}_{frame_index}.jpg"


def reference_pose(
    spec: CameraSpec, position: Position, yaw: float, tilt: float
) -> NDArray[np.float64]:
    """The camera-to-world matrix of the reference's ``pose.<setting>`` columns."""
    rendered = spec.camera_to_world(position, yaw, tilt)
    pose = np.eye(4)
    pose[:3, :3] = _HABITAT_TO_Z_UP @ rendered[:3, :3] @ _OPENCV_TO_OPENGL
    pose[:3, 3] = _HABITAT_TO_Z_UP @ rendered[:3, 3]
    return pose


def level_state(spec: CameraSpec, pose: NDArray[np.floating[Any]]) -> AgentState:
    """The agent state whose level camera has the reference pose ``pose``: the inverse of
    :func:`reference_pose` at tilt 0, so a stored frame's view can be rendered again."""
    rendered = _HABITAT_TO_Z_UP.T @ np.asarray(pose[:3, :3], np.float64) @ _OPENCV_TO_OPENGL
    x, eye_y, z = (float(v) for v in _HABITAT_TO_Z_UP.T @ np.asarray(pose[:3, 3], np.float64))
    yaw = math.atan2(rendered[0, 2], rendered[0, 0])  # the turn's sin and cos
    return AgentState((x, eye_y - spec.height_m, z), yaw, 0.0)


def frame_columns(spec: CameraSpec) -> dict[str, tuple[str, list[int]]]:
    """Parquet column name -> (numpy dtype, shape of one frame's value)."""
    level, down = (camera_setting(spec, camera) for camera in CAMERAS)
    return {
        "action": ("int32", []),
        f"pose.{level}": ("float32", [4, 4]),
        f"pose.{down}": ("float32", [4, 4]),
        f"goal.{down}": ("int32", [2]),
        f"relative_goal_frame_id.{down}": ("int32", []),
        "frame_index": ("int64", []),
        "episode_index": ("int64", []),
    }


def frame_table(
    spec: CameraSpec, trajectory: Trajectory, episode_index: int, goals: Sequence[Goal]
) -> bytes:
    """The parquet file of one trajectory."""
    level, down = (camera_setting(spec, camera) for camera in CAMERAS)
    steps = trajectory.steps
    values: dict[str, list[Any]] = {
        "action": [NO_ACTION] + [int(step.action) for step in steps[:-1]],
        f"pose.{level}": [
            _pose_rows(spec, step.state.position, step.state.yaw, 0.0) for step in steps
        ],
        f"pose.{down}": [
            _pose_rows(spec, step.state.position, step.state.yaw, math.radians(DOWN_TILT_DEG))
            for step in steps
        ],
        f"goal.{down}": [list(goal.pixel) for goal in goals],
        f"relative_goal_frame_id.{down}": [goal.frames_ahead for goal in goals],
        "frame_index": list(range(len(steps))),
        "episode_index": [episode_index] * len(steps),
    }
    arrays = {}
    for name, (dtype, shape) in frame_columns(spec).items():
        arrow_type = pa.from_numpy_dtype(np.dtype(dtype))
        for size in reversed(shape):
            arrow_type = pa.list_(arrow_type, size)
        arrays[name] = pa.array(values[name], type=arrow_type)
    sink = pa.BufferOutputStream()
    pq.write_table(pa.table(arrays), sink, compression="zstd")
    return bytes(sink.getvalue().to_pybytes())


def _pose_rows(spec: CameraSpec, position: Position, yaw: float, tilt: float) -> list[list[float]]:
    return [[float(v) for v in row] for row in reference_pose(spec, position, yaw, tilt)]


def episode_row(trajectory: Trajectory, index: int) -> dict[str, Any]:
    """The episodes.jsonl row: the reference's fields, then what our tools also use.

    ``nav_idx`` indexes ``path_node_to_frame``, the frames at which questions were asked, in
    asking order (the reference's path-node-to-frame table); ``true_idx`` is that frame.
    """
    episode = trajectory.episode
    nodes: list[int] = []
    dialogs: list[dict[str, Any]] = []
    for turn in trajectory.dialog:
        if turn.frame_index not in nodes:
            nodes.append(turn.frame_index)
        at = {"true_idx": turn.frame_index, "nav_idx": nodes.index(turn.frame_index)}
        dialogs.append(
            {"role": "navigator", "message": turn.question, **at, "trigger": turn.trigger}
        )
        dialogs.append(
            {"role": "oracle", "message": turn.answer, **at, "question_type": turn.question_type}
        )
    return {
        "episode_index": index,
        "tasks": [episode.instruction.instruction_text],
        "length": trajectory.length,
        "dialogs": dialogs,
        "path_node_to_frame": nodes,
        "episode_id": episode.episode_id,
        "scene_id": episode.scene_id,
        "target": {
            "instance_id": trajectory.target_key,
            "category": episode.object_category,
        },
        "path_length": round(trajectory.path_length, 4),
        "geodesic_distance": round(trajectory.steps[0].geodesic_distance, 4),
    }


def info_document(spec: CameraSpec) -> dict[str, Any]:
    """The fixed part of ``meta/info.json``: what the files hold and how to read them."""
    level, down = (camera_setting(spec, camera) for camera in CAMERAS)
    common = {"width": spec.width, "height": spec.height, "hfov_deg": spec.hfov_deg}
    features: dict[str, Any] = {
        name: {"dtype": dtype, "shape": shape or [1]}
        for name, (dtype, shape) in frame_columns(spec).items()
    }
    for setting in (level, down):
        features[f"observation.images.rgb.{setting}"] = {
            "dtype": "image",
            "shape": [spec.height, spec.width, 3],
        }
    return {
        "format_version": FORMAT_VERSION,
        "codebase_version": "v2.1",
        "chunks_size": CHUNK_SIZE,
        "data_path": "data/chunk-{episode_chunk:03d}/episode_{episode_index:06d}.parquet",
        "image_path": "videos/chunk-{episode_chunk:03d}/observation.images.rgb.{setting}/"
        "episode_{episode_index:06d}_{frame_index}.jpg",
        "cameras": {
            level: {**common, "height_m": spec.height_m, "pitch_deg": 0.0},
            down: {**common, "height_m": spec.height_m, "pitch_deg": -DOWN_TILT_DEG},
        },
        "pose": "camera-to-world 4x4; camera axes x right, y down, z forward (OpenCV); "
        "world x, y, z = habitat x, -z, y (z up), metres",
        "actions": {str(NO_ACTION): "none (first frame)"} | {str(int(a)): a.name for a in Action},
        "features": features,
    }
