"""The MP3D anchors are well-formed data and the comparison says which figures are in band."""

import pytest

from vlln.bench.anchors import ANCHORS, anchor, compare
from vlln.errors import ConfigError


def test_every_anchor_has_a_source_and_a_band_that_holds_its_value() -> None:
    names = [a.name for a in ANCHORS]
    assert len(names) == len(set(names))
    for a in ANCHORS:
        assert a.source.strip() and a.unit.strip(), a.name
        assert a.low <= a.value <= a.high, a.name


def test_compare_marks_figures_inside_and_outside_the_band() -> None:
    rooms, geodesic = anchor("regions_per_building"), anchor("start_to_target_geodesic_m")
    rows = {
        row["name"]: row
        for row in compare(
            {"regions_per_building": rooms.low, "start_to_target_geodesic_m": geodesic.high + 0.1}
        )
    }
    assert rows["regions_per_building"]["within"] is True
    assert rows["regions_per_building"]["measured"] == rooms.low
    assert (rows["regions_per_building"]["low"], rows["regions_per_building"]["high"]) == (
        rooms.low,
        rooms.high,
    )
    assert rows["start_to_target_geodesic_m"]["within"] is False
    assert rows["start_to_target_geodesic_m"]["anchor"] == geodesic.value


def test_compare_lists_every_anchor_and_leaves_unmeasured_ones_open() -> None:
    rows = compare({"instances_per_scene": 200.0})
    assert [row["name"] for row in rows] == [a.name for a in ANCHORS]
    unmeasured = [row for row in rows if row["name"] != "instances_per_scene"]
    assert all(row["measured"] is None and row["within"] is None for row in unmeasured)


def test_an_unknown_statistic_is_an_error_naming_the_known_ones() -> None:
    with pytest.raises(ConfigError, match="regions_per_building"):
        compare({"rooms_per_house": 7.0})
