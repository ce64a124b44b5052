"""What a room will contain: how many objects of each category, in which style, in what order.

Every category the catalogue allows in a room gets a Poisson number of instances (mean from
the category, times ``clutter``); a category a room type nearly always has appears once plus
a Poisson number with the rest of the mean, so a bathroom has one toilet, not three.
Instances of a category in one room often share a style, as matching dining chairs do.
Models are built here, so the placement order can put large things first and arrange some
categories around others (see :data:`ARRANGEMENTS`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vlln.world.catalogue.base import Category, ObjectModel, Placement, Style
from vlln.world.catalogue.registry import Catalogue
from vlln.world.generator.poses import LocalBounds
from vlln.world.model import Room

# Placement phases: what others depend on is placed first.
PHASE: dict[Placement, int] = {
    Placement.FLOOR: 0,
    Placement.AGAINST_WALL: 1,
    Placement.CORNER: 2,
    Placement.AT_TABLE: 3,
    Placement.WALL_MOUNTED: 4,
    Placement.CEILING: 5,
    Placement.ON_SURFACE: 6,
}
# category -> (the category it is arranged around, how): placed right after its anchor.
ARRANGEMENTS: dict[str, tuple[str, str]] = {
    "nightstand": ("bed", "beside"),
    "coffee table": ("couch", "in front"),
    "tv stand": ("couch", "across"),
    "range hood": ("stove", "above"),
}
COVERING_PHASE = 3.5  # rugs go down after the furniture that may not stand on them
STYLE_REUSE = 0.6  # chance that an instance takes its room's style for the category
EXPECTED_MEAN = 0.9  # a category this common in a room type appears at least once there
MANY_PER_ROOM = 1.5  # a category this common somewhere comes in numbers (chairs, pictures)
FLAT_HEIGHT = 0.05  # m; lower objects (rugs) are walked over and lie under furniture


@dataclass
class PlacementRequest:
    """An instance to place: its category, style and built model."""

    category: Category
    style: Style
    model: ObjectModel
    bounds: LocalBounds

    @property
    def footprint_area(self) -> float:
        return (self.bounds.hi[0] - self.bounds.lo[0]) * (self.bounds.hi[2] - self.bounds.lo[2])


def placement_phases(requests: list[PlacementRequest]) -> list[float]:
    """When each request is placed: by placement, rugs late, arranged ones after anchors."""
    phase = {r.category.name: float(PHASE[r.category.placement]) for r in requests}
    out = []
    for r in requests:
        name = r.category.name
        if r.bounds.height < FLAT_HEIGHT:
            out.append(COVERING_PHASE)
        elif name in ARRANGEMENTS and ARRANGEMENTS[name][0] in phase:
            out.append(max(phase[name], phase[ARRANGEMENTS[name][0]]) + 0.5)
        else:
            out.append(phase[name])
    return out


def draw_requests(
    room: Room,
    catalogue: Catalogue,
    clutter: float,
    rng: np.random.Generator,
    repeats: float = 1.0,
) -> list[PlacementRequest]:
    """The objects a room gets, with built models, in catalogue order; ``repeats`` multiplies
    the mean of categories that come in numbers (:data:`MANY_PER_ROOM`)."""
    requests = []
    for category in catalogue.for_room(room.type):
        mean = category.rooms[room.type] * clutter
        if max(category.rooms.values()) >= MANY_PER_ROOM:
            mean *= repeats
        if mean >= EXPECTED_MEAN:  # one for sure, more around the same mean
            count = 1 + int(rng.poisson(max(mean - 1.0, 0.0)))
        else:
            count = int(rng.poisson(mean))
        count = min(count, math.ceil(2.0 * mean) + 1)
        room_style = _draw_style(category, rng)
        for _ in range(count):
            style = room_style if rng.random() < STYLE_REUSE else _draw_style(category, rng)
            model = category.build(style, rng)
            lo, hi = model.mesh.bounds()
            bounds = LocalBounds(
                (float(lo[0]), float(lo[1]), float(lo[2])),
                (float(hi[0]), float(hi[1]), float(hi[2])),
            )
            requests.append(PlacementRequest(category, style, model, bounds))
    return requests


def _draw_style(category: Category, rng: np.random.Generator) -> Style:
    shapes = list(category.shapes)
    return Style(
        color=category.colors[int(rng.integers(len(category.colors)))],
        material=category.materials[int(rng.integers(len(category.materials)))],
        shape=shapes[int(rng.integers(len(shapes)))],
        scale=round(float(rng.uniform(0.85, 1.15)), 3),
    )
