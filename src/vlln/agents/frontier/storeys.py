"""The storeys the agent has stood on, told apart by the height of its feet.

The agent starts on storey 0, at height 0. It is on the known storey whose floor is nearest
its feet, so halfway down a flight it passes to the storey below when it knows that one. A
storey it does not know yet is found when the feet keep one height, more than
``NEW_STOREY`` from every known floor, over two forward moves in a row: a tread is shorter
than two moves, so only a floor keeps the height that long. Each storey keeps its own map
and explorer, whether its frontiers ran out, and where its flights lead once taken.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from vlln.agents.frontier.explorer import Explorer
from vlln.agents.frontier.mapping import ObstacleMap
from vlln.world.model import nearest_floor

NEW_STOREY = 1.0  # m: a floor this far from every known one is a new storey
_SAME_HEIGHT = 1e-3  # m
_FORWARD = 0.2  # m: a move that got this far went forward
_ON_FLOOR = 0.3  # m: an object whose lowest point is this far below a floor still stands on it


@dataclass
class Storey:
    """One storey: its floor's height above the start, its map and explorer."""

    floor: float
    map: ObstacleMap
    explorer: Explorer
    exhausted: bool = False  # its explorer found no frontier left


class StoreyMemory:
    """The known storeys, the one the agent is on, and the flights between them."""

    def __init__(self, new_storey: Callable[[float], Storey]) -> None:
        self._new_storey = new_storey
        self.storeys: list[Storey] = [new_storey(0.0)]
        self.current = 0
        self.links: dict[tuple[int, int], int] = {}  # (storey, +1 up / -1 down) -> storey
        self._last: tuple[float, float, float] | None = None
        self._level_moves = 0

    @property
    def here(self) -> Storey:
        return self.storeys[self.current]

    def observe(self, x: float, z: float, height: float) -> bool:
        """Follow the feet to ``height`` at (x, z); True when the storey changed."""
        last = self._last
        self._last = (x, z, height)
        if last is not None and math.hypot(x - last[0], z - last[1]) >= _FORWARD:
            level = abs(height - last[2]) < _SAME_HEIGHT
            self._level_moves = self._level_moves + 1 if level else 0
        floors = [storey.floor for storey in self.storeys]
        if self._level_moves >= 2 and min(abs(height - f) for f in floors) > NEW_STOREY:
            self.storeys.append(self._new_storey(height))
            floors.append(height)
        nearest = nearest_floor(floors, height)
        changed = nearest != self.current
        self.current = nearest
        return changed

    def on_floor(self, height: float) -> bool:
        """Whether the feet stand at the current storey's floor height (off the flight)."""
        return abs(height - self.here.floor) < _SAME_HEIGHT

    def storey_of(self, lowest: float) -> int | None:
        """The known storey an object whose lowest point is at ``lowest`` stands on."""
        under = [k for k, s in enumerate(self.storeys) if s.floor <= lowest + _ON_FLOOR]
        return max(under, key=lambda k: self.storeys[k].floor) if under else None

    def link(self, start: int, direction: int, end: int) -> None:
        """The flight that goes ``direction`` from ``start`` arrives at ``end``."""
        self.links[(start, direction)] = end
        self.links[(end, -direction)] = start
