"""Which boxes are certainly hidden behind what a depth image already shows.

A box is hidden when its nearest point is farther than the farthest surface drawn anywhere
in the screen rectangle it covers: then none of what it holds can pass the depth test. The
test is conservative (a hidden box may be kept, a visible one never dropped), so skipping the
hidden boxes leaves the image unchanged. Rectangle maxima come from
a max-pyramid over blocks of pixels, nine look-ups per box, for all boxes at once.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from vlln.sim.camera import CameraSpec, Position

BLOCK = 8  # pixels per side of the blocks whose farthest depth the test works with
_CORNER_BITS = np.array(list(np.ndindex(2, 2, 2)), np.float64)  # the 8 corners of a box
DEPTH_MARGIN = 0.01  # m a box must lie beyond the drawn surfaces to count as hidden


class FarthestDepth:
    """The farthest depth over rectangles of a z-depth image, from a max-pyramid.

    Level 0 holds the farthest depth of each block of ``BLOCK`` pixels, each further level the
    farthest of 2 x 2 cells of the one below. A rectangle is answered at the level where it
    spans at most three cells each way, from those (up to) nine cells: never nearer than the
    truth, which is all the test needs. Pixels with nothing drawn (depth 0) and those at the
    renderer's ``max_depth`` (which stands for anything farther) count as infinitely far.
    """

    def __init__(self, depth: NDArray[np.float32], max_depth: float) -> None:
        h, w = depth.shape
        rows, cols = -(-h // BLOCK), -(-w // BLOCK)
        padded = depth
        if (h, w) != (rows * BLOCK, cols * BLOCK):
            padded = np.zeros((rows * BLOCK, cols * BLOCK), np.float32)  # nothing drawn there
            padded[:h, :w] = depth
        # numpy reduces fast along long axes and slowly along short ones: the rows of a block
        # are reduced as whole image rows, its columns as strided slices.
        strips = padded.reshape(rows, BLOCK, cols * BLOCK)
        row_max, row_min = strips.max(axis=1), strips.min(axis=1)
        farthest = np.maximum.reduce([row_max[:, i::BLOCK] for i in range(BLOCK)])
        nearest = np.minimum.reduce([row_min[:, i::BLOCK] for i in range(BLOCK)])
        level = np.where((nearest <= 0.0) | (farthest >= max_depth), np.inf, farthest)
        levels = [level.astype(np.float64)]
        while max(levels[-1].shape) > 1:
            below = levels[-1]
            r, c = below.shape
            even = np.full((r + r % 2, c + c % 2), np.inf)
            even[:r, :c] = below
            top = np.maximum(even[0::2, 0::2], even[0::2, 1::2])
            levels.append(np.maximum(top, np.maximum(even[1::2, 0::2], even[1::2, 1::2])))
        self._offsets = np.cumsum([0] + [lv.size for lv in levels])
        self._widths = np.array([lv.shape[1] for lv in levels])
        self._cells = np.concatenate([lv.ravel() for lv in levels])
        self._top = len(levels) - 1
        self.shape = (h, w)

    def maximum(
        self,
        row_lo: NDArray[np.int64],
        row_hi: NDArray[np.int64],
        col_lo: NDArray[np.int64],
        col_hi: NDArray[np.int64],
    ) -> NDArray[np.float64]:
        """Farthest depth (or more) in each pixel rectangle ``[row_lo, row_hi] x [col_lo,
        col_hi]``, bounds included."""
        r0, r1, c0, c1 = row_lo // BLOCK, row_hi // BLOCK, col_lo // BLOCK, col_hi // BLOCK
        span = np.maximum(r1 - r0, c1 - c0) + 1
        # At this level a rectangle spans at most three cells each way.
        level = np.clip(np.ceil(np.log2(span)).astype(np.int64) - 1, 0, self._top)
        base, width = self._offsets[level], self._widths[level]
        r0, r1, c0, c1 = r0 >> level, r1 >> level, c0 >> level, c1 >> level
        row_starts = [base + r * width for r in (r0, np.minimum(r0 + 1, r1), r1)]
        cols = (c0, np.minimum(c0 + 1, c1), c1)
        cells = self._cells[np.stack([r + c for r in row_starts for c in cols])]
        farthest: NDArray[np.float64] = cells.max(axis=0)
        return farthest


def hidden_boxes(
    depth: FarthestDepth,
    spec: CameraSpec,
    position: Position,
    yaw: float,
    tilt: float,
    lows: NDArray[np.float64],
    highs: NDArray[np.float64],
) -> NDArray[np.bool_]:
    """For each axis-aligned box ``lows[k]..highs[k]``, whether ``depth`` hides all of it."""
    if len(lows) == 0:
        return np.zeros(0, np.bool_)
    corners = lows[:, None, :] + _CORNER_BITS * (highs - lows)[:, None, :]  # (n, 8, 3)
    view = spec.view_matrix(position, yaw, tilt)
    camera = (corners.reshape(-1, 3) @ view[:3, :3].T + view[:3, 3]).reshape(-1, 8, 3)
    z = -camera[..., 2]
    nearest = z.min(axis=1)
    in_front = nearest > spec.near  # a box reaching behind the near plane is never hidden
    safe_z = np.where(in_front[:, None], z, 1.0)
    fx, fy, cx, cy = spec.intrinsics()
    columns = cx + fx * camera[..., 0] / safe_z
    rows = cy - fy * camera[..., 1] / safe_z
    h, w = depth.shape
    # One pixel of margin around the projected corners covers every pixel the box touches.
    col_lo = np.clip(np.floor(columns.min(axis=1)) - 1, 0, w - 1).astype(np.int64)
    col_hi = np.clip(np.ceil(columns.max(axis=1)) + 1, 0, w - 1).astype(np.int64)
    row_lo = np.clip(np.floor(rows.min(axis=1)) - 1, 0, h - 1).astype(np.int64)
    row_hi = np.clip(np.ceil(rows.max(axis=1)) + 1, 0, h - 1).astype(np.int64)
    farthest = depth.maximum(row_lo, row_hi, col_lo, col_hi)
    # The margin keeps surfaces that only depth-buffer rounding would have hidden.
    hidden: NDArray[np.bool_] = in_front & (nearest > farthest * (1.0 + 1e-3) + DEPTH_MARGIN)
    return hidden
