"""Top-down maps of single episodes, drawn from an episode record and its house alone.

The record stores the pose after every movement step (``positions``: x, z, yaw) and every
action, so the map needs no replay: the trajectory is the positions, and a question's place is
the position at the moment its TALK action was issued. The floor plan comes from
:func:`vlln.viz.topdown.draw_house` with the target highlighted; same-category distractors,
the object the agent stopped at, the start and the end are marked on top. The map uses pose
coordinates (x to the right, z downwards, so -z is up), as every top-down view of the project.
"""

from __future__ import annotations

from pathlib import Path

from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from vlln.sim.agent import Action
from vlln.tasks.record import EpisodeRecord
from vlln.viz.topdown import draw_house, north_up
from vlln.world.model import House, ObjectInstance

_MOVES = {Action.MOVE_FORWARD.name, Action.TURN_LEFT.name, Action.TURN_RIGHT.name}


def question_positions(record: EpisodeRecord) -> list[tuple[float, float]]:
    """The (x, z) where each question of ``record.dialog`` was asked, in dialog order."""
    if not record.positions:
        return []
    places: list[tuple[float, float]] = []
    index = 0
    for action in record.actions:
        if action in _MOVES:
            index = min(index + 1, len(record.positions) - 1)
        elif action == "TALK":
            x, z = record.positions[index][0], record.positions[index][1]
            places.append((x, z))
    return places[: len(record.dialog)]


def draw_episode_map(
    record: EpisodeRecord, house: House, path: Path, title: str, mark_stop_object: bool = True
) -> None:
    """Write a PNG map of one episode (see module doc); ``mark_stop_object`` outlines the
    object the agent stopped at when it is not a goal (useful for failures only)."""
    xs = [p[0] for room in house.rooms for p in room.polygon]
    zs = [p[1] for room in house.rooms for p in room.polygon]
    span_x, span_z = max(xs) - min(xs), max(zs) - min(zs)
    scale = 9.0 / max(span_x, span_z, 1.0)
    fig = Figure(figsize=(max(4.5, span_x * scale), max(4.5, span_z * scale) + 0.8))
    ax = fig.subplots()
    draw_house(ax, house, label_objects=False, highlight=record.target_ids)
    targets = set(record.target_ids)
    distractors = [i for i in house.instances_of(record.object_category) if i.id not in targets]
    for k, inst in enumerate(distractors):
        _outline(ax, inst, "#ff7f0e", "same-category distractor" if k == 0 else None)
    for target_id in record.target_ids[:1]:
        target = house.instance(target_id)
        _outline(ax, target, "#d62728", f"target: {target.category}")
    stop_id = record.stop_instance_id
    if mark_stop_object and stop_id is not None and stop_id not in targets:
        _outline(ax, house.instance(stop_id), "#000000", "stopped at")
    if record.positions:
        path_x = [p[0] for p in record.positions]
        path_z = [p[1] for p in record.positions]
        ax.plot(path_x, path_z, color="#1f3fbf", linewidth=1.6, alpha=0.9, label="trajectory")
        ax.plot(path_x[0], path_z[0], "o", color="#2ca02c", markersize=10, label="start", zorder=5)
        ax.plot(path_x[-1], path_z[-1], "X", color="#111111", markersize=9, label="end", zorder=5)
    for k, ((x, z), turn) in enumerate(
        zip(question_positions(record), record.dialog, strict=False), start=1
    ):
        ax.plot(x, z, "D", color="#e377c2" if turn.answered else "#aaaaaa", markersize=6)
        ax.annotate(f"Q{k}", (x, z), textcoords="offset points", xytext=(5, 5), fontsize=8)
    if record.dialog:
        ax.plot([], [], "D", color="#e377c2", label="question (answered)")
    north_up(ax)
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


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
