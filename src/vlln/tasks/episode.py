"""Episode records and the released episode files (``{split}_{iign|ign}.json.gz``).

A file is gzip-compressed JSON ``{"episodes": [...]}``; each episode is::

    {"episode_id": str, "scene_id": str, "start_position": [x, y, z],
     "start_rotation": [x, y, z, w], "object_category": str,
     "goals": [{"position": [x, y, z], "radius": float | null,
                "bbox": [minx, miny, minz, maxx, maxy, maxz],
                "view_points": [{"agent_state": {"position": [x, y, z]}}, ...]}, ...],
     "instruction": {"task_type": str, "instruction_text": str, "instance_id": [str, ...],
                     "instruction_info": [str, ...] | null}}

in the Habitat frame that vlln uses throughout (:mod:`vlln.world.frame`); ``goals[0]`` is the
target. Extra keys of our own go into :attr:`Episode.info`, written as the episode's ``"info"``
key only when it is not empty; the reference loader (a Habitat ``Episode``) accepts ``info``,
so such files still load there. A top-level ``"category_to_task_category_id"``, which the
reference loader also accepts, is ignored. Anything else the reference would choke on is a
:class:`DataFormatError` naming the file, the episode (index and id), the field, and what
was expected.

Writing is atomic and deterministic: the same episodes give the same bytes (key order fixed,
gzip header time 0, no file name in the header), and a file is checked by the reader's rules
before it is written, so everything written can be read back.
"""

from __future__ import annotations

import gzip
import json
import math
import zlib
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from vlln.errors import DataFormatError
from vlln.files import write_bytes_atomic
from vlln.world.model import Point3

Quaternion = tuple[float, float, float, float]  # [x, y, z, w]
BBox = tuple[float, float, float, float, float, float]  # [minx, miny, minz, maxx, maxy, maxz]

_IGNORED_TOP_LEVEL_KEYS = ("category_to_task_category_id",)


@dataclass(frozen=True)
class ViewPoint:
    """A navigable position from which the goal counts as reached."""

    position: Point3


@dataclass(frozen=True)
class Goal:
    """One goal instance: its centre, box and view points (``radius`` may be unknown)."""

    position: Point3
    radius: float | None
    bbox: BBox
    view_points: tuple[ViewPoint, ...]


@dataclass(frozen=True)
class Instruction:
    """What the agent is told; ``instruction_info`` lists the attributes already stated."""

    task_type: str
    instruction_text: str
    instance_id: tuple[str, ...]  # target instance ids, as object_dict.json keys
    instruction_info: tuple[str, ...] | None = None


@dataclass(frozen=True)
class Episode:
    """One start pose, its goals and its instruction; ``info`` holds keys of our own."""

    episode_id: str
    scene_id: str
    start_position: Point3
    start_rotation: Quaternion
    object_category: str
    goals: tuple[Goal, ...]
    instruction: Instruction
    info: dict[str, Any] = field(default_factory=dict, hash=False)

    def to_json(self) -> dict[str, Any]:
        """The episode as the released format's JSON object."""
        data: dict[str, Any] = {
            "episode_id": self.episode_id,
            "scene_id": self.scene_id,
            "start_position": list(self.start_position),
            "start_rotation": list(self.start_rotation),
            "object_category": self.object_category,
            "goals": [
                {
                    "position": list(goal.position),
                    "radius": goal.radius,
                    "bbox": list(goal.bbox),
                    "view_points": [
                        {"agent_state": {"position": list(vp.position)}} for vp in goal.view_points
                    ],
                }
                for goal in self.goals
            ],
            "instruction": {
                "task_type": self.instruction.task_type,
                "instruction_text": self.instruction.instruction_text,
                "instance_id": list(self.instruction.instance_id),
                "instruction_info": None
                if self.instruction.instruction_info is None
                else list(self.instruction.instruction_info),
            },
        }
        if self.info:
            data["info"] = self.info
        return data

    @staticmethod
    def from_json(data: Any, where: str = "episode") -> Episode:
        """Parse one episode object; errors start with ``where``."""
        try:
            return _parse_episode(data)
        except _FieldError as err:
            shown = repr(err.got) if len(repr(err.got)) <= 80 else repr(err.got)[:77] + "..."
            raise DataFormatError(
                f"{where}: field {err.field!r}: expected {err.expected}, got {shown}"
            ) from None


def read_episodes(path: str | Path) -> list[Episode]:
    """Read a gzip JSON episode file."""
    path = Path(path)
    try:
        raw = gzip.decompress(path.read_bytes())
    except FileNotFoundError:
        raise DataFormatError(f"{path} does not exist") from None
    except IsADirectoryError:
        raise DataFormatError(f"{path} is a folder; give an episode file (.json.gz)") from None
    except (gzip.BadGzipFile, EOFError, zlib.error) as err:
        raise DataFormatError(
            f"{path} is not a gzip file ({err}); episode files are gzip-compressed JSON"
        ) from None
    try:
        data = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as err:
        raise DataFormatError(f"{path} does not hold UTF-8 JSON: {err}") from None
    return _parse_file(data, str(path))


def write_episodes(path: str | Path, episodes: Iterable[Episode]) -> None:
    """Write episodes to ``path`` atomically; the same episodes always give the same bytes."""
    path = Path(path)
    items = [episode.to_json() for episode in episodes]
    try:
        text = json.dumps({"episodes": items}, allow_nan=False)
    except (TypeError, ValueError) as err:
        raise DataFormatError(f"cannot write episodes to {path}: {err}") from None
    _parse_file(json.loads(text), f"episodes for {path}")
    blob = gzip.compress(text.encode("utf-8"), compresslevel=9, mtime=0)
    write_bytes_atomic(path, blob)


# --- validation -------------------------------------------------------------------------


class _Absent:
    def __repr__(self) -> str:
        return "no such key"


class _FieldError(Exception):
    """A field that does not follow the format; turned into a DataFormatError with context."""

    def __init__(self, field: str, expected: str, got: Any) -> None:
        super().__init__(field)
        self.field, self.expected, self.got = field, expected, got


def _parse_file(data: Any, source: str) -> list[Episode]:
    if not isinstance(data, dict) or "episodes" not in data:
        raise DataFormatError(f"{source}: expected a JSON object with an 'episodes' list")
    unknown = sorted(set(data) - {"episodes", *_IGNORED_TOP_LEVEL_KEYS})
    if unknown:
        raise DataFormatError(f"{source}: unknown top-level keys {unknown}; expected 'episodes'")
    if not isinstance(data["episodes"], list):
        raise DataFormatError(f"{source}: 'episodes' must be a list, got {data['episodes']!r:.80}")
    episodes = []
    for index, item in enumerate(data["episodes"]):
        episode_id = item.get("episode_id") if isinstance(item, dict) else None
        episodes.append(
            Episode.from_json(item, f"{source}: episode {index} (episode_id {episode_id!r})")
        )
    return episodes


def _check_keys(
    data: Any, name: str, required: tuple[str, ...], optional: tuple[str, ...] = ()
) -> dict[str, Any]:
    if not isinstance(data, dict):
        raise _FieldError(name or "episode", "a JSON object", data)
    prefix = f"{name}." if name else ""
    unknown = sorted(set(data) - set(required) - set(optional))
    if unknown:
        raise _FieldError(
            prefix + unknown[0], f"only the keys {[*required, *optional]}", data[unknown[0]]
        )
    for key in required:
        if key not in data:
            raise _FieldError(prefix + key, "a value", _Absent())
    return data


def _text(value: Any, name: str) -> str:
    if not isinstance(value, str):
        raise _FieldError(name, "a string", value)
    return value


def _numbers(value: Any, name: str, count: int) -> tuple[float, ...]:
    if not (
        isinstance(value, list)
        and len(value) == count
        and all(
            isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
            for v in value
        )
    ):
        raise _FieldError(name, f"a list of {count} finite numbers", value)
    return tuple(float(v) for v in value)


def _point(value: Any, name: str) -> Point3:
    x, y, z = _numbers(value, name, 3)
    return (x, y, z)


def _texts(value: Any, name: str) -> tuple[str, ...]:
    if not isinstance(value, list):
        raise _FieldError(name, "a list of strings", value)
    return tuple(_text(v, f"{name}[{i}]") for i, v in enumerate(value))


def _parse_episode(data: Any) -> Episode:
    optional = ("info",)
    required = (
        "episode_id",
        "scene_id",
        "start_position",
        "start_rotation",
        "object_category",
        "goals",
        "instruction",
    )
    data = _check_keys(data, "", required, optional)
    goals = data["goals"]
    if not isinstance(goals, list) or not goals:
        raise _FieldError("goals", "a non-empty list of goals (goals[0] is the target)", goals)
    info = data.get("info")
    if info is not None and not isinstance(info, dict):
        raise _FieldError("info", "a JSON object or null", info)
    x, y, z, w = _numbers(data["start_rotation"], "start_rotation", 4)
    return Episode(
        episode_id=_text(data["episode_id"], "episode_id"),
        scene_id=_text(data["scene_id"], "scene_id"),
        start_position=_point(data["start_position"], "start_position"),
        start_rotation=(x, y, z, w),
        object_category=_text(data["object_category"], "object_category"),
        goals=tuple(_parse_goal(goal, f"goals[{i}]") for i, goal in enumerate(goals)),
        instruction=_parse_instruction(data["instruction"]),
        info=dict(info or {}),
    )


def _parse_goal(data: Any, name: str) -> Goal:
    data = _check_keys(data, name, ("position", "radius", "bbox", "view_points"))
    radius = data["radius"]
    if radius is not None:
        (radius,) = _numbers([radius], f"{name}.radius", 1)
    bbox = _numbers(data["bbox"], f"{name}.bbox", 6)
    view_points = data["view_points"]
    if not isinstance(view_points, list):
        raise _FieldError(f"{name}.view_points", "a list of view points", view_points)
    points = []
    for i, view_point in enumerate(view_points):
        vp_name = f"{name}.view_points[{i}]"
        state = _check_keys(view_point, vp_name, ("agent_state",))["agent_state"]
        state = _check_keys(state, f"{vp_name}.agent_state", ("position",))
        points.append(ViewPoint(_point(state["position"], f"{vp_name}.agent_state.position")))
    return Goal(
        position=_point(data["position"], f"{name}.position"),
        radius=radius,
        bbox=(bbox[0], bbox[1], bbox[2], bbox[3], bbox[4], bbox[5]),
        view_points=tuple(points),
    )


def _parse_instruction(data: Any) -> Instruction:
    required = ("task_type", "instruction_text", "instance_id")
    data = _check_keys(data, "instruction", required, ("instruction_info",))
    info = data.get("instruction_info")
    return Instruction(
        task_type=_text(data["task_type"], "instruction.task_type"),
        instruction_text=_text(data["instruction_text"], "instruction.instruction_text"),
        instance_id=_texts(data["instance_id"], "instruction.instance_id"),
        instruction_info=None if info is None else _texts(info, "instruction.instruction_info"),
    )
