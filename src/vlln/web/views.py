"""What each page receives, as JSON-ready dicts.

The navigator's view is built from an allow-list: the instruction, the camera image, counts
and the dialog, never the target, a position, the instance-id image or the map (a test reads
the raw payloads to hold this). The oracle's view adds what the reference's annotators had:
the target, the navigator's pose and trail, and the house map (:func:`oracle_map`). In a
house with several storeys the oracle sees the storey the navigator is on: its map, and the
part of the trail walked there.
"""

from __future__ import annotations

import base64
import io
from typing import Any

import matplotlib

matplotlib.use("Agg")
import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from PIL import Image

from vlln.tasks.spec import TaskType
from vlln.viz.topdown import draw_house, storey_name
from vlln.web.session import EpisodeSession, Status

MAP_PIXELS = 1000  # the longer side of the oracle's map image
MAP_MARGIN = 0.4  # metres around the rooms


def jpeg_data_url(rgb: np.ndarray, quality: int) -> str:
    buffer = io.BytesIO()
    Image.fromarray(rgb).save(buffer, format="JPEG", quality=quality)
    return "data:image/jpeg;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")


def _frame_url(session: EpisodeSession, key: tuple[str, int], rgb: np.ndarray | None) -> str | None:
    if rgb is None:
        return None
    cached = session.frame_cache
    if cached is None or cached[0] != key:
        cached = (key, jpeg_data_url(rgb, session.config.jpeg_quality))
        session.frame_cache = cached
    return cached[1]


def _common(session: EpisodeSession) -> dict[str, Any]:
    view = session.view
    config = session.config
    result = None
    if view.status in (Status.FINISHED, Status.ABANDONED):
        result = {"success": view.success, "end_reason": view.end_reason, "error": view.error}
    return {
        "version": session.signal.version,
        "status": view.status,
        "instruction": session.episode.instruction.instruction_text,
        "steps": view.steps,
        "max_steps": config.max_steps,
        "questions_left": view.questions_left,
        "budget": session.spec.budget,
        "dialog_enabled": config.task == TaskType.IIGN and session.spec.budget > 0,
        "oracle": session.oracle_kind.value,
        "dialog": [
            {"question": q, "answer": a, "answered": answered} for q, a, answered in view.dialog
        ],
        "result": result,
    }


def navigator_view(session: EpisodeSession) -> dict[str, Any]:
    """The navigator page's payload (module doc: an allow-list, nothing privileged)."""
    with session.lock:
        payload = _common(session)
        payload["frame_number"] = session.view.frame_number
        payload["frame"] = _frame_url(session, ("now", session.view.frame_number), session.view.rgb)
    return payload


def oracle_view(session: EpisodeSession) -> dict[str, Any]:
    """The oracle page's payload: the common part plus the pose, the trail, the target and
    the pending question with the view it was asked from."""
    pending = session.board.pending()
    with session.lock:
        payload = _common(session)
        view = session.view
        if pending is not None:
            frame = _frame_url(session, ("question", pending.number), pending.frame.rgb)
        else:
            frame = _frame_url(session, ("now", view.frame_number), view.rgb)
        payload["frame"] = frame
        payload["pose"] = list(view.pose)
        payload["trail"] = [
            list(point)
            for point, storey in zip(view.trail, view.trail_storeys, strict=True)
            if storey == view.storey
        ]
        if view.storey is not None:
            payload["storey"] = view.storey
    payload["time_limit_s"] = session.config.answer_time_limit_s
    payload["question"] = (
        None
        if pending is None
        else {
            "number": pending.number,
            "text": pending.text,
            "seconds_left": round(pending.seconds_left(), 1),
        }
    )
    target, house = session.target, session.house
    if target is not None and house is not None:
        attributes = {k: v for k, v in vars(target.attributes).items() if v}
        room = next((r.type for r in house.rooms if r.id == target.room_id), "")
        payload["target"] = {
            "category": target.category,
            "caption": target.caption,
            "attributes": attributes,
            "room": room,
        }
    return payload


def oracle_map(session: EpisodeSession) -> dict[str, Any]:
    """The house from above with the target in red, as a PNG data URL, and the map's extent
    ``[x_min, x_max, y_min, y_max]`` in (x, -z) metres, for drawing the trail over it. In a
    house with several storeys: the storey the navigator is on, named in ``storey`` (its
    number) and ``storey_name``; the extent is the whole house's, the same for every storey."""
    with session.lock:
        storey = session.view.storey
    cached = session.map_cache.get(storey)
    if cached is not None:
        return cached
    house, target = session.house, session.target
    if house is None:
        raise RuntimeError("the session's house is not built yet; wait for session.ready")
    xs = [p[0] for room in house.rooms for p in room.polygon]
    ys = [-p[1] for room in house.rooms for p in room.polygon]
    x0, x1 = min(xs) - MAP_MARGIN, max(xs) + MAP_MARGIN
    y0, y1 = min(ys) - MAP_MARGIN, max(ys) + MAP_MARGIN
    scale = MAP_PIXELS / max(x1 - x0, y1 - y0)
    dpi = 180  # object labels at a readable size in pixels
    figure = Figure(figsize=((x1 - x0) * scale / dpi, (y1 - y0) * scale / dpi), dpi=dpi)
    axes = figure.add_axes((0.0, 0.0, 1.0, 1.0))
    draw_house(
        axes, house, label_objects=True, highlight=[target.id] if target else [], storey=storey
    )
    if target is not None:
        (bx0, _, bz0), (bx1, _, bz1) = target.box.min, target.box.max
        # On another storey than the target's, a dashed outline says where it is above or below.
        level = next((room.level for room in house.rooms if room.id == target.room_id), storey)
        elsewhere = storey is not None and level is not None and level != storey
        axes.add_patch(
            Rectangle(
                (bx0 - 0.15, bz0 - 0.15),
                bx1 - bx0 + 0.3,
                bz1 - bz0 + 0.3,
                fill=False,
                edgecolor="#d62728",
                linewidth=3.0,
                linestyle="--" if elsewhere else "-",
            )
        )
        if elsewhere and level is not None:
            axes.text(
                (bx0 + bx1) / 2.0,
                bz1 + 0.3,
                f"{target.category}: on the {storey_name(level)}",
                ha="center",
                va="top",
                fontsize=7,
                color="#d62728",
                fontweight="bold",
                bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none", "pad": 1.0},
            )
    axes.set_aspect("auto")  # the figure already has the house's proportions: fill it
    axes.set_xlim(x0, x1)
    axes.set_ylim(-y0, -y1)  # the map is drawn in pose coordinates: z down, -z up
    axes.set_axis_off()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=dpi)
    image = "data:image/png;base64," + base64.b64encode(buffer.getvalue()).decode("ascii")
    drawn: dict[str, Any] = {"image": image, "extent": [x0, x1, y0, y1]}
    if storey is not None:
        drawn |= {"storey": storey, "storey_name": storey_name(storey)}
    session.map_cache[storey] = drawn
    return drawn
