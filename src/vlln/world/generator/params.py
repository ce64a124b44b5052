"""The knobs of the procedural house generator and the rules that make a set of them valid.

Validation happens before any house is drawn so that an impossible request (twelve rooms in
sixty square metres) fails at once with a message that names the parameter and the fix,
instead of producing a degenerate house or looping forever.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

from vlln.errors import HouseParametersError

# Smallest mean floor area per room (corridor share included) that the floor planner can
# always lay out with doors, a corridor and furniture that still leaves a walkable floor.
MIN_AREA_PER_ROOM = 7.0
# Largest mean floor area per room: bigger rooms would be empty halls for the furnisher.
MAX_AREA_PER_ROOM = 50.0
# Shortest side of any room; a door needs this much wall plus its corner margins.
MIN_ROOM_SIDE = 1.7
# A door keeps this distance from each room corner it is next to.
DOOR_CORNER_MARGIN = 0.3
# The agent is 0.36 m wide; a door opening must leave it room to pass.
MIN_DOOR_WIDTH = 0.85


@dataclass(frozen=True)
class HouseParameters:
    """What a user can ask of a generated house; every house drawn with them satisfies them."""

    min_rooms: int = field(default=4, metadata={"help": "fewest rooms (corridor included)"})
    max_rooms: int = field(default=12, metadata={"help": "most rooms (corridor included)"})
    min_area: float = field(default=60.0, metadata={"help": "smallest total floor area, m²"})
    max_area: float = field(default=250.0, metadata={"help": "largest total floor area, m²"})
    ceiling_height: float = field(default=2.7, metadata={"help": "floor to ceiling, m"})
    wall_thickness: float = field(default=0.1, metadata={"help": "thickness of every wall, m"})
    door_width: float = field(default=0.9, metadata={"help": "clear width of door openings, m"})
    clutter: float = field(
        default=1.0, metadata={"help": "multiplies the mean number of objects per room"}
    )
    floors: int = field(default=1, metadata={"help": "storeys joined by stairs (1 to 3)"})
    repeats: float = field(
        default=1.0,
        metadata={
            "help": "multiplies the mean number of objects that come in numbers (categories "
            "with >= 1.5 per room on average: chairs, books, pictures, pillows, ...)"
        },
    )
    category_variety: float = field(
        default=1.0,
        metadata={
            "help": "share of the optional categories a house draws its objects from "
            "(lower: fewer kinds, more same-category distractors)"
        },
    )

    def validate(self) -> None:
        """Raise :class:`HouseParametersError` naming the first parameter that cannot work."""
        _check_int("min_rooms", self.min_rooms, 1, 40)
        _check_int("max_rooms", self.max_rooms, 1, 40)
        if self.min_rooms > self.max_rooms:
            raise HouseParametersError(
                f"min_rooms={self.min_rooms} is larger than max_rooms={self.max_rooms}; "
                f"set min_rooms <= max_rooms"
            )
        _check_number("min_area", self.min_area, 10.0, 1000.0)
        _check_number("max_area", self.max_area, 10.0, 1000.0)
        if self.min_area > self.max_area:
            raise HouseParametersError(
                f"min_area={self.min_area} m² is larger than max_area={self.max_area} m²; "
                f"set min_area <= max_area"
            )
        needed = self.min_rooms * MIN_AREA_PER_ROOM
        if self.max_area < needed:
            fitting = max(1, math.floor(self.max_area / MIN_AREA_PER_ROOM))
            raise HouseParametersError(
                f"min_rooms={self.min_rooms} rooms cannot fit in max_area={self.max_area} m²: "
                f"rooms need >= {MIN_AREA_PER_ROOM:g} m² each on average; raise max_area to "
                f">= {needed:g} or lower min_rooms to <= {fitting}"
            )
        largest = self.max_rooms * MAX_AREA_PER_ROOM
        if self.min_area > largest:
            raise HouseParametersError(
                f"min_area={self.min_area} m² with max_rooms={self.max_rooms} would make rooms "
                f"of more than {MAX_AREA_PER_ROOM:g} m² on average; lower min_area to "
                f"<= {largest:g} or raise max_rooms to >= "
                f"{math.ceil(self.min_area / MAX_AREA_PER_ROOM)}"
            )
        _check_number("ceiling_height", self.ceiling_height, 2.3, 4.0)
        _check_number("wall_thickness", self.wall_thickness, 0.05, 0.25)
        widest = MIN_ROOM_SIDE - 2.0 * DOOR_CORNER_MARGIN - self.wall_thickness
        if not MIN_DOOR_WIDTH <= self.door_width <= widest:
            raise HouseParametersError(
                f"door_width={self.door_width} m is outside [{MIN_DOOR_WIDTH}, {widest:.2f}]: "
                f"a door must let the 0.36 m wide agent pass and fit in the shortest room "
                f"side ({MIN_ROOM_SIDE} m) with {DOOR_CORNER_MARGIN} m from each corner and "
                f"wall_thickness={self.wall_thickness}; use a door_width in that range (thinner "
                f"walls allow wider doors)"
            )
        _check_number("clutter", self.clutter, 0.0, 3.0)
        _check_int("floors", self.floors, 1, 3)
        _check_number("category_variety", self.category_variety, 0.1, 1.0)
        _check_number("repeats", self.repeats, 0.0, 4.0)


@dataclass(frozen=True)
class ParameterInfo:
    """One settable parameter, for command-line help and configuration files."""

    name: str
    type: str
    default: float | int
    help: str


def describe_parameters() -> list[ParameterInfo]:
    """Every parameter of :class:`HouseParameters` with its type, default and meaning."""
    defaults = HouseParameters()
    return [
        ParameterInfo(f.name, str(f.type), getattr(defaults, f.name), f.metadata["help"])
        for f in fields(HouseParameters)
    ]


def _check_int(name: str, value: object, low: int, high: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int):
        raise HouseParametersError(
            f"{name}={value!r} must be a whole number in [{low}, {high}]; pass an int"
        )
    if not low <= value <= high:
        raise HouseParametersError(
            f"{name}={value} is outside the valid range [{low}, {high}]; choose a value in it"
        )


def _check_number(name: str, value: object, low: float, high: float) -> None:
    if isinstance(value, bool) or not isinstance(value, int | float) or math.isnan(value):
        raise HouseParametersError(f"{name}={value!r} must be a number in [{low:g}, {high:g}]")
    if not low <= value <= high:
        raise HouseParametersError(
            f"{name}={value:g} is outside the valid range [{low:g}, {high:g}]; choose a value in it"
        )


def parameters_from_overrides(overrides: list[str]) -> HouseParameters:
    """Parameters from ``NAME=VALUE`` strings (the command line's ``--param``), validated."""
    values: dict[str, int | float] = {}
    known = {f.name: f for f in fields(HouseParameters)}
    for item in overrides:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or name not in known:
            raise HouseParametersError(
                f"cannot use house parameter {item!r}; write NAME=VALUE with NAME one of: "
                f"{', '.join(known)}"
            )
        kind = int if isinstance(getattr(HouseParameters(), name), int) else float
        try:
            values[name] = kind(text)
        except ValueError:
            expected = "a whole number" if kind is int else "a number"
            raise HouseParametersError(
                f"house parameter {name}={text!r} must be {expected}"
            ) from None
    params = HouseParameters(**values)  # type: ignore[arg-type]
    params.validate()
    return params
