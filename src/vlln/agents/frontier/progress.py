"""The agent's last moves, to tell when it is stuck."""

from __future__ import annotations

import math
from collections import deque


class Trail:
    """Where the last ``steps`` counted moves started and whether each went forward."""

    def __init__(self, steps: int, distance: float) -> None:
        self.steps = steps
        self.distance = distance
        self._moves: deque[tuple[float, float, bool]] = deque(maxlen=steps)

    def add(self, x: float, z: float, forward: bool) -> None:
        self._moves.append((x, z, forward))

    def clear(self) -> None:
        self._moves.clear()

    def stuck(self) -> bool:
        """Mostly forward moves over the last steps, yet hardly any way made: walking into
        something the map does not show, or back and forth between two plans. The trail
        starts afresh when it says so."""
        moves = self._moves
        if len(moves) < self.steps:
            return False
        forwards = sum(1 for _, _, forward in moves if forward)
        moved = math.hypot(moves[-1][0] - moves[0][0], moves[-1][1] - moves[0][1])
        if 3 * forwards >= 2 * len(moves) and moved < self.distance:
            moves.clear()
            return True
        return False
