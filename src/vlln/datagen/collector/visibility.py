"""How much of an object a frame shows in its middle: the test the final frames must pass.

The final view counts as showing the target when either camera does: the level one, or the
one tilted 30° down that both the dataset and the model's look-down prompt use (low objects
close by are seen only by the latter).
"""

from __future__ import annotations

import math

import numpy as np

from vlln.sim.renderer import Frame


def central_pixels(frame: Frame, instance_id: int) -> int:
    """Pixels of the instance inside rows H/8..7H/8 and columns W/8..7W/8 (the central
    3/4 x 3/4 of the image)."""
    h, w = frame.instance_ids.shape
    centre = frame.instance_ids[h // 8 : h - h // 8, w // 8 : w - w // 8]
    return int(np.count_nonzero(centre == instance_id))


DOWN_TILT_DEG = -30.0  # the look-down camera's pitch
DOWN_TILT = math.radians(DOWN_TILT_DEG)


def best_central_pixels(frames: tuple[Frame, ...], instance_id: int) -> int:
    """The most central pixels of the instance over several views of one moment."""
    return max(central_pixels(frame, instance_id) for frame in frames)
