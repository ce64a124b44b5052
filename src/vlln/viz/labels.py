"""Labels that never cover each other: each is tried at its place and a few nudges away, and
left out when every try would overlap a label already drawn.

Matplotlib places no labels itself; this runs once the figure's layout is final (text sizes
in pixels are known only then) and takes labels in the order given, so the important ones
(rooms, then large objects) keep their places. Saving at another dpi scales text and axes
alike, so labels that do not overlap here do not overlap in the PNG.
"""

from __future__ import annotations

from collections.abc import Sequence

from matplotlib.figure import Figure
from matplotlib.text import Text
from matplotlib.transforms import Bbox, ScaledTranslation

# nudges in points: at the anchor, above, below, right, left
_NUDGES = ((0.0, 0.0), (0.0, 6.0), (0.0, -6.0), (12.0, 0.0), (-12.0, 0.0))
_PAD = 1.0  # pixels kept free around a label


def declutter(fig: Figure, fixed: Sequence[Text], movable: Sequence[Text]) -> int:
    """Keep ``fixed`` labels where they are; nudge or hide each of ``movable`` (most
    important first) so that no two labels overlap. Returns how many were hidden."""
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    placed: list[Bbox] = [text.get_window_extent(renderer).padded(_PAD) for text in fixed]
    hidden = 0
    for text in movable:
        base = text.get_transform()
        for dx, dy in _NUDGES:
            text.set_transform(base + ScaledTranslation(dx / 72, dy / 72, fig.dpi_scale_trans))
            box = text.get_window_extent(renderer).padded(_PAD)
            if not any(box.overlaps(other) for other in placed):
                placed.append(box)
                break
        else:
            text.set_transform(base)
            text.set_visible(False)
            hidden += 1
    return hidden
