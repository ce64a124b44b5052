"""Top-down maps of single episodes, drawn from an episode record and its house alone.

The record stores the pose after every movement step (``positions``: x, z, yaw) and every
action, so the map needs no replay: the trajectory is the positions, and a question's place is
the position at the moment its TALK action was issued. The floor plan comes from
:func:`vlln.viz.topdown.draw_house` with the target highlighted; same-category distractors,
the object the agent stopped at, the start and the end are marked on top. The map uses pose
coordinates (x to the right, z downwards, so -z is up), as every top-down view of the project.

A house with several storeys gets one panel per storey, side by side. Each pose's storey comes
from its recorded height (``heights``): the trail, start, end, questions and objects are drawn
on the panel of the storey they are on, so a climb leaves one panel at the stairs and enters
the next there.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from vlln.files import writing
from vlln.sim.agent import Action
from vlln.tasks.record import EpisodeRecord
from vlln.viz.topdown import (
    draw_house,
    north_up,
    stands_on,
    storey_at_height,
    storey_name,
    storeys_of,
)
from vlln.world.model import House, ObjectInstance

_MOVES = {Action.MOVE_FORWARD.name, Action.TURN_LEFT.name, Action.TURN_RIGHT.name}


def question_poses(record: EpisodeRecord) -> list[int]:
    """The index into ``positions`` of the pose where each question of ``record.dialog`` was
    asked (the position at the moment its TALK action was issued), in dialog order."""
    if not record.positions:
        return []
    poses: list[int] = []
    index = 0
    for action in record.actions:
        if action in _MOVES:
            index = min(index + 1, len(record.positions) - 1)
        elif action == "TALK":
            poses.append(index)
    return poses[: len(record.dialog)]


def question_positions(record: EpisodeRecord) -> list[tuple[float, float]]:
    """The (x, z) where each question of ``record.dialog`` was asked, in dialog order."""
    return [(record.positions[i][0], record.positions[i][1]) for i in question_poses(record)]


def pose_storeys(record: EpisodeRecord, house: House) -> list[int] | None:
    """The storey of every recorded pose; None when the house has several storeys and the
    record holds no heights (a record written before heights were recorded)."""
    storeys = storeys_of(house)
    if len(storeys) == 1:
        return storeys * len(record.positions)
    if len(record.heights) != len(record.positions):
        return None
    return [storey_at_height(house, y) for y in record.heights]


def draw_episode_map(
    record: EpisodeRecord, house: House, path: Path, title: str, mark_stop_object: bool = True
) -> None:
    """Write a PNG map of one episode (see module doc); ``mark_stop_object`` outlines the
    object the agent stopped at when it is not a goal (useful for failures only)."""
    xs = [p[0] for room in house.rooms for p in room.polygon]
    zs = [p[1] for room in house.rooms for p in room.polygon]
    span_x, span_z = max(xs) - min(xs), max(zs) - min(zs)
    storeys = storeys_of(house)
    levels = pose_storeys(record, house)
    if len(storeys) == 1:
        scale = 9.0 / max(span_x, span_z, 1.0)
        fig = Figure(figsize=(max(4.5, span_x * scale), max(4.5, span_z * scale) + 0.8))
        axes = [fig.subplots()]
    else:
        scale = 6.0 / max(span_x, span_z, 1.0)
        width = max(3.5, span_x * scale)
        fig = Figure(figsize=(width * len(storeys), max(3.5, span_z * scale) + 0.9))
        axes = list(fig.subplots(1, len(storeys)))
        if levels is None:
            title += " (storeys of the poses not recorded: trail shown on every storey)"
    for ax, storey in zip(axes, storeys, strict=True):
        _draw_storey(ax, record, house, storey, levels, mark_stop_object)
        ax.set_title(storey_name(storey) if len(storeys) > 1 else title, fontsize=9)
    if len(storeys) > 1:
        fig.suptitle(title, fontsize=9)
    handles: dict[str, Any] = {}
    for ax in axes:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, handle)
    axes[-1].legend(
        list(handles.values()),
        list(handles),
        loc="upper left",
        bbox_to_anchor=(1.0, 1.0),
        fontsize=7,
    )
    fig.tight_layout()
    with writing(path):
        fig.savefig(path, dpi=110)


def _draw_storey(
    ax: Axes,
    record: EpisodeRecord,
    house: House,
    storey: int,
    levels: list[int] | None,
    mark_stop_object: bool,
) -> None:
    """One storey's panel: its plan, the objects on it and the part of the trail there."""
    several = len(storeys_of(house)) > 1
    draw_house(
        ax, house, label_objects=False, highlight=record.target_ids,
        storey=storey if several else None,
    )  # fmt: skip

    def here(inst: ObjectInstance) -> bool:
        return not several or stands_on(house, inst, storey)

    def on_storey(pose: int) -> bool:
        return levels is None or levels[pose] == storey

    targets = set(record.target_ids)
    distractors = [i for i in house.instances_of(record.object_category) if i.id not in targets]
    for k, inst in enumerate(i for i in distractors if here(i)):
        _outline(ax, inst, "#ff7f0e", "same-category distractor" if k == 0 else None)
    for target_id in record.target_ids[:1]:
        target = house.instance(target_id)
        if here(target):
            _outline(ax, target, "#d62728", f"target: {target.category}")
    stop_id = record.stop_instance_id
    stopped_at = house.instance(stop_id) if stop_id is not None else None
    if mark_stop_object and stopped_at is not None and stop_id not in targets and here(stopped_at):
        _outline(ax, stopped_at, "#000000", "stopped at")
    if record.positions:
        for run in _runs(range(len(record.positions)), on_storey):
            ax.plot(
                [record.positions[i][0] for i in run],
                [record.positions[i][1] for i in run],
                color="#1f3fbf", linewidth=1.6, alpha=0.9, label="trajectory",
            )  # fmt: skip
        first, last = record.positions[0], record.positions[-1]
        if on_storey(0):
            ax.plot(
                first[0], first[1], "o", color="#2ca02c", markersize=10, label="start", zorder=5
            )
        if on_storey(len(record.positions) - 1):
            ax.plot(*last[:2], "X", color="#111111", markersize=9, label="end", zorder=5)
    for k, (pose, turn) in enumerate(
        zip(question_poses(record), record.dialog, strict=False), start=1
    ):
        if not on_storey(pose):
            continue
        x, z = record.positions[pose][0], record.positions[pose][1]
        ax.plot(x, z, "D", color="#e377c2" if turn.answered else "#aaaaaa", markersize=6)
        ax.annotate(f"Q{k}", (x, z), textcoords="offset points", xytext=(5, 5), fontsize=8)
    if any(turn.answered for turn in record.dialog):
        ax.plot([], [], "D", color="#e377c2", label="question (answered)")
    if not all(turn.answered for turn in record.dialog):
        ax.plot([], [], "D", color="#aaaaaa", label="question (refused)")
    north_up(ax)


def _runs(poses: range, keep: Callable[[int], bool]) -> list[list[int]]:
    """Maximal runs of consecutive poses that ``keep`` accepts (a trail's pieces on a storey)."""
    runs: list[list[int]] = []
    for pose in poses:
        if not keep(pose):
            continue
        if runs and runs[-1][-1] == pose - 1:
            runs[-1].append(pose)
        else:
            runs.append([pose])
    return runs


def _outline(ax: Axes, inst: ObjectInstance, color: str, label: str | None) -> None:
    (x0, _, z0), (x1, _, z1) = inst.box.min, inst.box.max
    patch = Rectangle(
        (x0 - 0.1, z0 - 0.1),
        x1 - x0 + 0.2,
        z1 - z0 + 0.2,
        fill=False,
        edgecolor=color,
        linewidth=2.0,
        label=label,
    )
    ax.add_patch(patch)
