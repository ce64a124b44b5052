"""Top-down maps of a house: rooms labelled, doors, object footprints and, optionally, the
navigable area and paths. The evaluation report draws trajectories on the same map."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle

from vlln.files import writing
from vlln.sim.navgrid import NavGrid
from vlln.sim.storeys import Storeys
from vlln.viz.labels import declutter
from vlln.world.model import House, ObjectInstance, nearest_floor

ROOM_LABEL = "room-label"
OBJECT_LABEL = "object-label"
ROOM_COLORS = {
    "living room": "#f6e7c8",
    "bedroom": "#dfe8f7",
    "kitchen": "#e3f3dc",
    "dining room": "#f7e0d8",
    "bathroom": "#d8f1f3",
    "toilet": "#e6e0f5",
    "study": "#f3efd6",
    "corridor": "#ececec",
    "storage room": "#e8e2da",
    "gym": "#f5dcea",
}


def draw_house(
    ax: Axes,
    house: House,
    grid: NavGrid | None = None,
    label_objects: bool = True,
    highlight: Sequence[int] = (),
    storey: int | None = None,
) -> None:
    """Draw the floor plan on ``ax`` in pose coordinates, as seen from above: x to the right
    and z downwards, so -z (where yaw 0 looks) is up and a point read off the map is an
    (x, z) a pose can use. Call :func:`declutter_map` once the figure's layout is final.

    ``storey`` draws one storey of a house with several: its rooms, doors and objects, and
    the stairs that reach it."""
    rooms = [room for room in house.rooms if storey is None or room.level == storey]
    on_storey = {room.id for room in rooms}
    for room in rooms:
        xs = [p[0] for p in room.polygon]
        zs = [p[1] for p in room.polygon]
        ax.add_patch(
            Polygon(
                np.c_[xs, zs],
                closed=True,
                facecolor=ROOM_COLORS.get(room.type, "#eeeeee"),
                edgecolor="#444444",
                linewidth=1.5,
            )
        )
        ax.text(
            float(np.mean(xs)),
            float(np.mean(zs)),
            f"{room.type}\n#{room.id}",
            ha="center",
            va="center",
            fontsize=8,
            color="#555555",
            alpha=0.8,
            gid=ROOM_LABEL,
        )
    if grid is not None:
        x0, z0 = grid.origin
        h, w = grid.shape
        extent = (x0, x0 + w * grid.cell_size, z0 + h * grid.cell_size, z0)
        overlay = np.where(grid.navigable, 0.0, np.nan)
        ax.imshow(
            overlay,
            extent=extent,
            origin="upper",
            cmap="Greens",
            vmin=-1.0,
            vmax=1.0,
            alpha=0.25,
            interpolation="nearest",
        )
    for door in house.doors:
        if door.room_a not in on_storey and door.room_b not in on_storey:
            continue
        ax.plot(door.center[0], door.center[1], marker="s", color="#8b5a2b", markersize=5)
    chosen = set(highlight)
    shown = [inst for inst in house.instances if storey is None or stands_on(house, inst, storey)]
    by_size = sorted(shown, key=lambda inst: -inst.box.size[0] * inst.box.size[2])
    for inst in by_size:
        (x0, _, z0), (x1, _, z1) = inst.box.min, inst.box.max
        is_chosen = inst.id in chosen
        ax.add_patch(
            Rectangle(
                (x0, z0),
                x1 - x0,
                z1 - z0,
                facecolor="#d62728" if is_chosen else "#1f77b4",
                alpha=0.7 if is_chosen else 0.35,
                edgecolor="#222222",
                linewidth=0.4,
            )
        )
        if label_objects:
            ax.text(
                (x0 + x1) / 2,
                (z0 + z1) / 2,
                inst.category,
                ha="center",
                va="center",
                fontsize=4.5,
                color="#000000",
                gid=OBJECT_LABEL,
            )
    ax.set_aspect("equal")
    ax.autoscale_view()
    north_up(ax)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")


def north_up(ax: Axes) -> None:
    """Put -z up (once, however often it is called)."""
    if not ax.yaxis_inverted():
        ax.invert_yaxis()


def declutter_map(fig: Figure) -> int:
    """Nudge or hide object labels so that none overlaps another or a room label (larger
    objects first); returns how many were hidden."""
    texts = [text for ax in fig.axes for text in ax.texts]
    rooms = [text for text in texts if text.get_gid() == ROOM_LABEL]
    objects = [text for text in texts if text.get_gid() == OBJECT_LABEL]
    return declutter(fig, rooms, objects)


def storeys_of(house: House) -> list[int]:
    """The house's storeys, lowest first (``[0]`` for a house of one)."""
    return sorted({room.level for room in house.rooms}) or [0]


def storey_at_height(house: House, y: float) -> int:
    """The storey whose floor is nearest the height (the lower one on a tie), as the
    simulator assigns an agent halfway up a flight of stairs."""
    floors = {room.level: room.floor_y for room in house.rooms}
    levels = sorted(floors)
    return levels[nearest_floor([floors[level] for level in levels], y)] if levels else 0


def stands_on(house: House, inst: ObjectInstance, storey: int) -> bool:
    """Whether an object is drawn on a storey's map: it is in one of its rooms, or it is a
    flight of stairs whose top reaches the storey."""
    levels = {room.id: room.level for room in house.rooms}
    if inst.category == "stairs":
        floors = {room.level: room.floor_y for room in house.rooms}
        top = floors.get(storey)
        if top is not None and abs(inst.box.max[1] - top) < 0.05:
            return True
    return levels.get(inst.room_id, 0) == storey


def storey_name(storey: int) -> str:
    return (
        ("ground floor", "first floor", "second floor")[storey] if storey < 3 else f"floor {storey}"
    )


def house_figure(
    house: House, grid: NavGrid | Storeys | None = None, title: str | None = None
) -> Figure:
    """The map of a house; one panel per storey, side by side, when it has several."""
    xs = [p[0] for r in house.rooms for p in r.polygon]
    zs = [p[1] for r in house.rooms for p in r.polygon]
    span_x = max(xs) - min(xs) if xs else 10.0
    span_z = max(zs) - min(zs) if zs else 10.0
    scale = 12.0 / max(span_x, span_z, 1.0)
    storeys = sorted({room.level for room in house.rooms})
    heading = title or f"{house.name}: {len(house.rooms)} rooms, {len(house.instances)} objects"
    if len(storeys) > 1:
        width = max(4.0, span_x * scale * 0.6)
        fig, axes = plt.subplots(
            1, len(storeys), figsize=(width * len(storeys), max(4.0, span_z * scale * 0.6) + 0.9)
        )
        for ax, storey in zip(axes, storeys, strict=True):
            plane = grid.grids[storey] if isinstance(grid, Storeys) else None
            draw_house(ax, house, plane, storey=storey)
            ax.set_title(storey_name(storey))
        fig.suptitle(heading)
        fig.tight_layout()
        declutter_map(fig)
        return fig
    fig, ax = plt.subplots(figsize=(max(4.0, span_x * scale), max(4.0, span_z * scale) + 0.6))
    draw_house(ax, house, grid if isinstance(grid, NavGrid) else None)
    ax.set_title(heading)
    fig.tight_layout()
    declutter_map(fig)
    return fig


def save_house_map(house: House, path: Path, grid: NavGrid | Storeys | None = None) -> None:
    fig = house_figure(house, grid)
    try:
        with writing(path):
            path.parent.mkdir(parents=True, exist_ok=True)
            fig.savefig(path, dpi=150)
    finally:
        plt.close(fig)
