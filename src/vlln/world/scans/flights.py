"""Flights of stairs in a scan: the instance that joins one storey to the next.

A scan's stairs (mpcat40 ``stairs``, whatever their raw name: ``steps``, ``step``,
``staircase``...; HM3D's ``stairs`` objects) come in as an instance of category ``stairs``
whose triangles are the flight, which is what the simulator climbs (:mod:`vlln.sim.storeys`):
it walks on the flight's flat, up-facing faces (its treads) and joins the two storeys whose
floors are at the flight's foot and top. Ordinary stairs end with a rise onto the upper floor,
which is their top landing, and a scan's box around them ends below that floor: a top within
one step below the floor arrives on it (:func:`vlln.world.model.top_at`), as a foot within one
step above a floor starts from it. A flight that cannot be climbed (its foot or top on no
floor, treads that are not flat, as in a noisy scan) is not imported as stairs:
:func:`flight_problem` says why, and the import keeps its triangles as the house's shell, so
the storeys stay apart.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from vlln.world.model import MAX_RISE, foot_on, top_at

FLIGHT_CATEGORY = "stairs"  # every flight's instance category (vlln.world.scans.categories)
MIN_TREAD_SHARE = 0.5  # of a flight's up-facing plan area, at least this much is flat treads


def flight_problem(triangles: NDArray[np.float64], floor_ys: list[float]) -> str | None:
    """Why the flight made of ``triangles`` cannot join two storeys whose floors are among
    ``floor_ys`` (ascending), or ``None`` when it can."""
    if len(triangles) == 0:
        return "it has no triangles"
    heights = triangles[:, :, 1]
    low, high = float(heights.min()), float(heights.max())
    floors = ", ".join(f"{y:.3f}" for y in floor_ys)
    foot = next((k for k, y in enumerate(floor_ys) if foot_on(y, low)), None)
    if foot is None:
        return f"its foot ({low:.3f} m) is on no storey's floor ({floors} m)"
    if foot + 1 >= len(floor_ys) or not top_at(floor_ys[foot + 1], high):
        return f"its top ({high:.3f} m) is not the floor of the storey above its foot ({floors} m)"
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    up_area = np.maximum(normals[:, 1], 0.0) / 2.0  # plan area of up-facing triangles
    flat = (np.ptp(heights, axis=1) == 0.0) & (up_area > 0.0)
    share = float(up_area[flat].sum() / max(up_area.sum(), 1e-12))
    if share < MIN_TREAD_SHARE:
        return (
            f"only {share:.0%} of its up-facing surface is flat treads (at least "
            f"{MIN_TREAD_SHARE:.0%} needed to walk on)"
        )
    treads = np.unique(heights[flat, 0])
    rises = np.diff(np.concatenate([[floor_ys[foot]], treads, [floor_ys[foot + 1]]]))
    if float(rises.max()) > MAX_RISE:
        return f"a step rises {float(rises.max()):.2f} m (at most {MAX_RISE} m)"
    return None


def taller_than_a_step(triangles: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Per triangle, whether it rises more than a step: a wall beside the flight or under its
    landing that the flight's box takes in, which must stay a wall (treads and risers never
    rise that much)."""
    rise: NDArray[np.bool_] = np.ptp(triangles[:, :, 1], axis=1) > MAX_RISE
    return rise
