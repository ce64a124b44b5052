"""What a catalogue category is: its variants, where it goes, and how its model is built.

A category's builder turns a :class:`Style` (colour, material, shape, scale) into an
:class:`ObjectModel` in the model's local frame:

* the base's centre is at the origin, standing on ``y = 0``;
* the front faces +z and the back is at -z, so an object placed against a wall has its back
  to the wall (the generator rotates and moves it, see :meth:`vlln.world.mesh.Mesh.transformed`);
* sizes are in metres and already include ``style.scale``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

from vlln.world.mesh import Mesh


class Placement(StrEnum):
    """Where the generator puts instances of a category."""

    AGAINST_WALL = "against the wall"  # on the floor, back to a wall
    FLOOR = "on the floor"  # on the floor, free-standing (rugs, tables, beds, islands)
    AT_TABLE = "at the table"  # on the floor, facing a table of the room (chairs, stools)
    CORNER = "in the corner"  # on the floor, in a room corner
    ON_SURFACE = "on a surface"  # on a table, counter, shelf or nightstand
    WALL_MOUNTED = "on the wall"  # hung on a wall at a category-given height
    CEILING = "on the ceiling"  # hanging from the ceiling


@dataclass(frozen=True)
class Style:
    """The variation the generator draws for one instance."""

    color: str
    material: str
    shape: str
    scale: float = 1.0  # multiplies the nominal size; 0.85..1.15

    @property
    def size_word(self) -> str:
        if self.scale < 0.95:
            return "small"
        if self.scale > 1.05:
            return "large"
        return "medium"


@dataclass(frozen=True)
class Surface:
    """A flat top where small objects can stand, in the model's local frame."""

    height: float
    center: tuple[float, float]  # (x, z)
    size: tuple[float, float]  # (width along x, depth along z)


@dataclass
class ObjectModel:
    """A built model: its mesh (instance id 0 until placed) and support surfaces."""

    mesh: Mesh
    surfaces: list[Surface] = field(default_factory=list)


Builder = Callable[[Style, np.random.Generator], ObjectModel]


@dataclass(frozen=True)
class Category:
    """One object category of the catalogue.

    ``shapes`` maps each shape word to the fine-grained category it makes (a "round" table is a
    "round table", an "office" chair an "office chair"). ``rooms`` maps room types to how many
    instances a room of that type gets on average; a category absent from a room type never
    appears there. ``wall_height`` is the height of a wall-mounted model's origin, the bottom
    centre of its back, above the floor.
    """

    name: str
    shapes: dict[str, str]
    colors: tuple[str, ...]
    materials: tuple[str, ...]
    placement: Placement
    rooms: dict[str, float]
    build: Builder
    wall_height: float = 1.5
