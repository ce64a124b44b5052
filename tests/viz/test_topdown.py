"""Top-down maps use the coordinates poses use, and their labels never overlap."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from vlln.viz.topdown import house_figure
from vlln.world.generator import generate_house


@pytest.mark.slow
def test_map_axes_are_pose_coordinates() -> None:
    """Reproduction 12: a point read off the map is an (x, z) a pose can use."""
    house = generate_house(0)
    fig = house_figure(house)
    ax = fig.axes[0]
    assert ax.get_ylabel() == "z (m)" and ax.get_xlabel() == "x (m)"
    assert ax.yaxis_inverted()  # -z (north, where yaw 0 looks) is up
    zs = [z for room in house.rooms for _, z in room.polygon]
    low, high = sorted(ax.get_ylim())
    assert low <= min(zs) and max(zs) <= high  # ticks read z itself, not -z
    room = house.rooms[0]
    patch = next(p for p in ax.patches if len(p.get_xy()) >= len(room.polygon))
    assert np.allclose(patch.get_xy()[: len(room.polygon)], room.polygon)


@pytest.mark.slow
def test_object_labels_do_not_overlap() -> None:
    """Reproduction 12: crowded labels are moved or left out, never drawn over each other."""
    fig = house_figure(generate_house(0))
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    shown = [text for text in fig.axes[0].texts if text.get_visible() and text.get_text()]
    assert len(shown) > 20
    boxes = [text.get_window_extent(renderer) for text in shown]
    for first, second in itertools.combinations(boxes, 2):
        assert not first.overlaps(second)
