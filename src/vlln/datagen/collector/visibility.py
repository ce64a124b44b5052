"""How much of an object a frame shows in its middle: the test the final frames must pass.

The final view counts as showing the target when either camera does: the level one, or the
one tilted 30° down that both the dataset and the model's look-down prompt use (low objects
close by are seen only by the latter).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray


def central_pixels(instance_ids: NDArray[np.int32], instance_id: int) -> int:
    """Pixels of the instance inside rows H/8..7H/8 and columns W/8..7W/8 (the central
    3/4 x 3/4 of a view's instance-id image). Only the ids are looked at, so a caller that
    renders a view for this test alone renders just them (``Simulator.render_instance_ids``,
    no shading)."""
    h, w = instance_ids.shape
    centre = instance_ids[h // 8 : h - h // 8, w // 8 : w - w // 8]
    return int(np.count_nonzero(centre == instance_id))


DOWN_TILT_DEG = -30.0  # the look-down camera's pitch
DOWN_TILT = math.radians(DOWN_TILT_DEG)


def best_central_pixels(views: tuple[NDArray[np.int32], ...], instance_id: int) -> int:
    """The most central pixels of the instance over the instance-id images of several views
    of one moment."""
    return max(central_pixels(ids, instance_id) for ids in views)
