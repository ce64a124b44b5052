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
so such files still load there.

Reading accepts every variant the reference accepts (docs/reference-formats.md §1): top-level extras
(``category_to_task_category``, ...) are ignored, and so are Habitat's episode extras
(:data:`IGNORED_EPISODE_KEYS`, InternNav's ``frames``) and Habitat's goal extras
(``object_id``, ``object_name``, ...); ``episode_id`` may be an integer; a goal may lack
``radius`` and ``bbox``, and its ``view_points`` may be empty (the environment computes
them); ``instruction_info`` may be missing or null; a missing or null ``object_category`` is
taken from the target goal's ``object_category``, else from an instance id such as
``"3/chair_12"``, else from an instruction "... the <category>.". Anything else the reference
would choke on is a :class:`DataFormatError` naming the file, the episode (index and id), the
field, and what was expected.

Writing follows the reference evaluator's conventions: decimal episode ids unique per file (it
calls ``int(episode_id)``), instructions ending with a full stop (it drops the last
character), and ``scene_id`` shaped ``<root>/<scene>/<scene>.glb`` (it takes the scene folder
as ``scene_id.split('/')[-2]``); :func:`reference_convention_problems` lists breaches, and the
split builder refuses to write episodes with any.

Writing is atomic and deterministic: the same episodes give the same bytes (key order fixed,
gzip header time 0, no file name in the header), and a file is checked by the reader's rules
before it is written, so everything written can be read back.
"""

from __future__ import annotations

import gzip
import json
import math
import re
import zlib
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, utf8_text, write_bytes_atomic
from vlln.tasks.episode_memory import MemoryBudget, OverBudget
from vlln.tasks.json_fields import (
    Absent,
    FieldError,
    check_keys,
    id_text_of,
    numbers_of,
    point_of,
    shown,
    text_of,
    texts_of,
)
from vlln.world.catalogue.aliases import canonical_category
from vlln.world.model import Point3

Quaternion = tuple[float, float, float, float]  # [x, y, z, w]
BBox = tuple[float, float, float, float, float, float]  # [minx, miny, minz, maxx, maxy, maxz]

IGNORED_EPISODE_KEYS = (
    "scene_dataset_config",
    "additional_obj_config_paths",
    "shortest_paths",
    "start_room",
    "frames",
)
IGNORED_GOAL_KEYS = (
    "object_id",
    "object_name",
    "object_name_id",
    "object_category",
    "room_id",
    "room_name",
)


@dataclass(frozen=True, slots=True)
class ViewPoint:
    """A navigable position from which the goal counts as reached."""

    position: Point3


@dataclass(frozen=True)
class Goal:
    """One goal instance: its centre, box and view points (``radius`` and ``bbox`` may be
    unknown; no view points means the environment computes them from the box)."""

    position: Point3
    radius: float | None
    bbox: BBox | None
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
            "goals": [_goal_json(goal) for goal in self.goals],
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
    def from_json(
        data: Any, where: str = "episode", shared_goals: dict[int, Goal] | None = None
    ) -> Episode:
        """Parse one episode object; errors start with ``where``. ``shared_goals`` maps the
        ids of goal objects (alive while the caller holds the document) to their parsed goals,
        so a goal object that several episodes share is parsed once."""
        try:
            return _parse_episode(data, shared_goals)
        except FieldError as err:
            raise DataFormatError(
                f"{where}: field {err.field!r}: expected {err.expected}, got {shown(err.got)}"
            ) from None


def _goal_json(goal: Goal) -> dict[str, Any]:
    data: dict[str, Any] = {"position": list(goal.position), "radius": goal.radius}
    if goal.bbox is not None:
        data["bbox"] = list(goal.bbox)
    data["view_points"] = [
        {"agent_state": {"position": list(vp.position)}} for vp in goal.view_points
    ]
    return data


# The benchmark's own files reach about 110 MB (the mp3d ObjectNav split of 30 houses: 108.8
# MB, view points mostly), so the cap admits them with room to spare and stops a gzip bomb.
EPISODE_FILE_CAP = ReadCap("an episode file", 128, "VLLN_MAX_EPISODE_FILE_MB")

# Parsed, JSON takes up to 24 times its bytes, so reading may also take at most this many bytes
# of memory a byte of the cap, charged before and while parsing (:mod:`.episode_memory`): 768
# MiB. Hostile files under the default cap (floats, integers, short, long or wide strings,
# objects, lists, keys, view points) peak at 732 MiB at most, interpreter included, where they
# took up to 2.1 GiB. Real files are charged more than they take: an ObjectNav split of 104 MiB
# (the size of the mp3d one) 555 MiB, peaking at 245; 2.35 million view points (121 MiB) 656
# MiB, peaking at 643.
MEMORY_PER_CAP_BYTE = 6


def read_episodes(path: str | Path) -> list[Episode]:
    """Read a gzip JSON episode file, at most :data:`EPISODE_FILE_CAP` of it, taking at most
    :data:`MEMORY_PER_CAP_BYTE` bytes of memory a byte of the cap."""
    path = Path(path)
    try:
        raw = EPISODE_FILE_CAP.read(path, gzipped=True)
    except FileNotFoundError:
        raise DataFormatError(f"{path} does not exist") from None
    except IsADirectoryError:
        raise DataFormatError(f"{path} is a folder; give an episode file (.json.gz)") from None
    except (gzip.BadGzipFile, EOFError, zlib.error) as err:
        raise DataFormatError(
            f"{path} is not a gzip file ({err}); episode files are gzip-compressed JSON"
        ) from None
    budget = MemoryBudget(path, EPISODE_FILE_CAP, MEMORY_PER_CAP_BYTE)
    budget.charge_text(raw)
    try:
        text = utf8_text(raw)
        del raw  # only the text is held while parsing
        data = parse_json(text, object_hook=_GoalSharing(budget))
    except OverBudget:
        raise
    except DataFormatError as err:
        raise DataFormatError(
            f"{path} does not hold UTF-8 JSON: {err}; give a released episode file"
        ) from None
    del text
    return _parse_file(data, str(path))


class _GoalSharing:
    """A JSON object hook that returns one object for goals that are equal, and tells a
    :class:`MemoryBudget` of the view point starts it does not make view points and the view
    points it lets go.

    ObjectNav episodes list every instance of their category as a goal, with all its view
    points, so a split repeats each goal in many episodes. Sharing the decoded goal as soon as
    it is complete lets the copy go at once, and parsing shares the :class:`Goal` too
    (:func:`_parse_file`): a 14-house split then reads in a fraction of the memory."""

    def __init__(self, budget: MemoryBudget | None = None) -> None:
        self._budget = budget  # None: a file this process wrote, read back
        self._seen: dict[tuple[Any, ...], list[dict[str, Any]]] = {}

    def __call__(self, obj: dict[str, Any]) -> dict[str, Any] | ViewPoint:
        view_point = _written_view_point(obj)
        if view_point is not None:  # decoded at once: a split holds hundreds of thousands
            return view_point  # charged with the text
        points = obj.get("view_points")
        if isinstance(points, list) and "position" in obj:
            key = (_numbers_key(obj.get("position")), _numbers_key(obj.get("bbox")), len(points))
            same = self._seen.setdefault(key, [])
            for earlier in same:
                if earlier == obj:
                    if self._budget is not None:
                        self._budget.refund_view_points(list(map(type, points)).count(ViewPoint))
                    return earlier
            same.append(obj)
        if "agent_state" in obj and self._budget is not None:
            self._budget.charge_start(obj)
        return obj


def _numbers_key(value: Any) -> str | None:
    """The repr of a short list of numbers, to find goals that may be equal; None for any other
    value, whose repr could take more memory than the value (a list of hostile length)."""
    if type(value) is list and len(value) <= 6 and all(type(v) in (float, int) for v in value):
        return repr(value)
    return None


def write_episodes(path: str | Path, episodes: Iterable[Episode]) -> None:
    """Write episodes to ``path`` atomically; the same episodes always give the same bytes."""
    path = Path(path)
    # Episode by episode, so a split whose ObjectNav goals list thousands of view points never
    # holds more than one episode as JSON objects; each is read back as a reader would.
    # Read back through the reader's own decoding, so a goal that episodes share is checked once.
    parts, sharing, shared_goals = [], _GoalSharing(), dict[int, Goal]()
    for index, episode in enumerate(episodes):
        try:
            part = json.dumps(episode.to_json(), allow_nan=False)
        except (TypeError, ValueError) as err:
            raise DataFormatError(f"cannot write episodes to {path}: {err}") from None
        where = f"episodes for {path}: episode {index} (episode_id {episode.episode_id!r})"
        Episode.from_json(json.loads(part, object_hook=sharing), where, shared_goals)
        parts.append(part)
    text = '{"episodes": [' + ", ".join(parts) + "]}"
    blob = gzip.compress(text.encode("utf-8"), compresslevel=9, mtime=0)
    write_bytes_atomic(path, blob)


def reference_convention_problems(episodes: Iterable[Episode]) -> list[str]:
    """What in these episodes the reference evaluator would misread (module doc), one line
    each; the split builder refuses to write episodes with any."""
    problems: list[str] = []
    seen: set[int] = set()
    for index, episode in enumerate(episodes):
        where = f"episode {index} (episode_id {episode.episode_id!r})"
        if not episode.episode_id.isdecimal() or int(episode.episode_id) in seen:
            problems.append(f"{where}: the id is not a decimal string unique in the file")
        else:
            seen.add(int(episode.episode_id))
        if not episode.instruction.instruction_text.endswith("."):
            problems.append(f"{where}: the instruction does not end with a full stop")
        parts = episode.scene_id.split("/")
        if len(parts) < 2 or parts[-1] != f"{parts[-2]}.glb":
            problems.append(
                f"{where}: scene_id {episode.scene_id!r} is not <root>/<scene>/<scene>.glb"
            )
    return problems


def scene_name(scene_id: str) -> str:
    """The scene a ``scene_id`` names, as the reference reads it: its folder, else its stem."""
    parts = scene_id.split("/")
    if len(parts) >= 2 and parts[-1].endswith(".glb"):
        return parts[-2]
    return parts[-1].removesuffix(".glb")


# --- validation -------------------------------------------------------------------------


def _parse_file(data: Any, source: str) -> list[Episode]:
    if not isinstance(data, dict) or "episodes" not in data:
        raise DataFormatError(f"{source}: expected a JSON object with an 'episodes' list")
    if not isinstance(data["episodes"], list):
        raise DataFormatError(f"{source}: 'episodes' must be a list, got {shown(data['episodes'])}")
    episodes = []
    shared: dict[int, Goal] = {}  # goal objects that _GoalSharing made one, parsed once
    for index, item in enumerate(data["episodes"]):
        episode_id = item.get("episode_id") if isinstance(item, dict) else None
        where = f"{source}: episode {index} (episode_id {shown(episode_id)})"
        episodes.append(Episode.from_json(item, where, shared_goals=shared))
    _check_unique_ids(episodes, source)
    return episodes


def _check_unique_ids(episodes: Sequence[Episode], source: str) -> None:
    """An episode id names one episode of a file (the reference evaluator keys on it, and a
    run's results on scene and id): a repeat would be played twice and counted once."""
    first: dict[str, int] = {}
    for index, episode in enumerate(episodes):
        earlier = first.setdefault(episode.episode_id, index)
        if earlier != index:
            raise DataFormatError(
                f"{source}: episodes {earlier} and {index} share episode_id "
                f"{shown(episode.episode_id)}; give each episode of the file its own id"
            )


def _parse_episode(data: Any, shared_goals: dict[int, Goal] | None = None) -> Episode:
    optional = ("info", "object_category")
    required = (
        "episode_id",
        "scene_id",
        "start_position",
        "start_rotation",
        "goals",
        "instruction",
    )
    data = check_keys(data, "", required, optional, IGNORED_EPISODE_KEYS)
    goals = data["goals"]
    if not isinstance(goals, list) or not goals:
        raise FieldError("goals", "a non-empty list of goals (goals[0] is the target)", goals)
    info = data.get("info")
    if info is not None and not isinstance(info, dict):
        raise FieldError("info", "a JSON object or null", info)
    x, y, z, w = numbers_of(data["start_rotation"], "start_rotation", 4)
    instruction = _parse_instruction(data["instruction"])
    return Episode(
        episode_id=id_text_of(data["episode_id"], "episode_id"),
        scene_id=text_of(data["scene_id"], "scene_id"),
        start_position=point_of(data["start_position"], "start_position"),
        start_rotation=(x, y, z, w),
        object_category=_category_of(data, instruction),
        goals=tuple(
            _shared_goal(goal, f"goals[{i}]", shared_goals) for i, goal in enumerate(goals)
        ),
        instruction=instruction,
        info=dict(info or {}),
    )


_INSTRUCTION_CATEGORY = re.compile(r"\bthe ([a-z][a-z ]*?)[.,;]", re.IGNORECASE)


def _category_of(data: dict[str, Any], instruction: Instruction) -> str:
    """The catalogue's name (aliases such as "sofa" mapped) of the episode's category."""
    return canonical_category(_named_category(data, instruction))


def _named_category(data: dict[str, Any], instruction: Instruction) -> str:
    """``object_category``, else the target goal's, else from an instance id, else the text."""
    given = data.get("object_category")
    if given is not None:
        return text_of(given, "object_category")
    target = data["goals"][0]
    from_goal = target.get("object_category") if isinstance(target, dict) else None
    if isinstance(from_goal, str) and from_goal:
        return from_goal
    for instance_id in instruction.instance_id:
        category = category_of_instance_key(instance_id)
        if category:
            return category
    match = _INSTRUCTION_CATEGORY.search(instruction.instruction_text)
    if match is not None:
        return match.group(1).strip().lower()
    raise FieldError(
        "object_category",
        "a category here, in goals[0].object_category, in an instance id such as "
        "'3/chair_12' or in an instruction '... the <category>.'",
        Absent(),
    )


def category_of_instance_key(key: str) -> str:
    """The category an instance id such as ``"3/chair_12"`` names (``""`` for ``"12"``)."""
    match = re.fullmatch(r"(?:.*/)?([^/]*?)_(\d+)", key)
    return "" if match is None else match.group(1).replace("_", " ")


def _shared_goal(data: Any, name: str, shared: dict[int, Goal] | None) -> Goal:
    if shared is None:
        return _parse_goal(data, name)
    goal = shared.get(id(data))
    if goal is None:
        goal = shared[id(data)] = _parse_goal(data, name)
    return goal


def _parse_goal(data: Any, name: str) -> Goal:
    data = check_keys(
        data, name, ("position",), ("radius", "bbox", "view_points"), IGNORED_GOAL_KEYS
    )
    radius = data.get("radius")
    if radius is not None:
        (radius,) = numbers_of([radius], f"{name}.radius", 1)
    bbox: BBox | None = None
    if data.get("bbox") is not None:
        b = numbers_of(data["bbox"], f"{name}.bbox", 6)
        bbox = (b[0], b[1], b[2], b[3], b[4], b[5])
    view_points = data.get("view_points") or []
    if not isinstance(view_points, list):
        raise FieldError(f"{name}.view_points", "a list of view points", view_points)
    points = []
    for i, view_point in enumerate(view_points):
        if isinstance(view_point, ViewPoint):  # the written shape, decoded by the reader
            points.append(view_point)
            continue
        vp_name = f"{name}.view_points[{i}]"  # another shape: checked, or what is wrong named
        state = check_keys(view_point, vp_name, ("agent_state",))["agent_state"]
        state = check_keys(state, f"{vp_name}.agent_state", ("position",), (), ("rotation",))
        points.append(ViewPoint(point_of(state["position"], f"{vp_name}.agent_state.position")))
    return Goal(
        position=point_of(data["position"], f"{name}.position"),
        radius=radius,
        bbox=bbox,
        view_points=tuple(points),
    )


def _written_view_point(data: Any) -> ViewPoint | None:
    """The view point of a JSON object in the shape :func:`write_episodes` gives it, checked
    without the general path's per-field names; None for any other shape."""
    if len(data) != 1:
        return None
    state = data.get("agent_state")
    if type(state) is not dict or len(state) != 1:
        return None
    position = state.get("position")
    if type(position) is not list or len(position) != 3:
        return None
    x, y, z = position
    if type(x) is float and type(y) is float and type(z) is float and math.isfinite(x + y + z):
        return ViewPoint((x, y, z))  # a finite sum: each is finite
    return None


def _parse_instruction(data: Any) -> Instruction:
    required = ("task_type", "instruction_text", "instance_id")
    data = check_keys(data, "instruction", required, ("instruction_info",))
    info = data.get("instruction_info")
    ids = data["instance_id"]
    if not isinstance(ids, list):
        raise FieldError("instruction.instance_id", "a list of instance ids", ids)
    return Instruction(
        task_type=text_of(data["task_type"], "instruction.task_type"),
        instruction_text=text_of(data["instruction_text"], "instruction.instruction_text"),
        instance_id=tuple(
            id_text_of(v, f"instruction.instance_id[{i}]") for i, v in enumerate(ids)
        ),
        instruction_info=None if info is None else texts_of(info, "instruction.instruction_info"),
    )
