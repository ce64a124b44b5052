"""The MP3D file readers compute the documented statistics from small files in the real formats."""

import json
from pathlib import Path

import pytest

from vlln.bench.mp3d_connectivity import building_graph, storeys
from vlln.bench.mp3d_house import house_stats
from vlln.cli import main
from vlln.errors import DataFormatError

# Two storeys: a 4 x 3 m kitchen and a 2 x 2 m junk region on level 0, a 5 x 4 m bedroom on
# level 1; token layout as in real files (valan r2r/testdata, niessner/Matterport docs).
HOUSE = """ASCII 1.1
H  -  -  0 0 3 3 0 7 5 3 0  2  0 0 0 0 0 0 0 0  5 4 6  0 0 0 0 0
L  0  0  -  2 1 0  0 0 0  4 3 3  0 0 0 0 0
L  1  0  -  2 2 3  0 0 3  5 4 6  0 0 0 0 0
R  0 0  0 0  k  2 1.5 0  0 0 0  4 3 2.5  2.5  0 0 0 0
R  1 0  0 0  Z  5 1 0  4 0 0  6 2 2.5  2.5  0 0 0 0
R  2 1  0 0  b  2.5 2 3  0 0 3  5 4 5.5  2.5  0 0 0 0
S  0 0  0  F  2 1.5 0  0 0 1  0 0 0  4 3 0  0 0 0 0 0
S  1 1  0  F  5 1 0  0 0 1  4 0 0  6 2 0  0 0 0 0 0
S  2 2  0  F  2.5 2 3  0 0 1  0 0 3  5 4 3  0 0 0 0 0
V  0 0  F  0 0 0  0 0 1  0 0 0
V  1 0  F  4 0 0  0 0 1  0 0 0
V  2 0  F  4 3 0  0 0 1  0 0 0
V  3 0  F  0 3 0  0 0 1  0 0 0
V  4 1  F  4 0 0  0 0 1  0 0 0
V  5 1  F  6 0 0  0 0 1  0 0 0
V  6 1  F  6 2 0  0 0 1  0 0 0
V  7 1  F  4 2 0  0 0 1  0 0 0
V  8 2  F  0 0 3  0 0 1  0 0 0
V  9 2  F  5 0 3  0 0 1  0 0 0
V  10 2  F  5 4 3  0 0 1  0 0 0
V  11 2  F  0 4 3  0 0 1  0 0 0
C  0  1 wall  1 wall  0 0 0 0 0
C  1  5 chair  3 chair  0 0 0 0 0
C  2  26 dining#chair  3 chair  0 0 0 0 0
C  3  41 unknown  40 misc  0 0 0 0 0
C  4  26 bed  11 bed  0 0 0 0 0
O  0 0 0  1 0 1  1 0 0  0 1 0  1 0.1 1 0 0 0 0 0 0 0 0
O  1 0 1  1 1 0.5  1 0 0  0 1 0  0.3 0.3 0.5 0 0 0 0 0 0 0 0
O  2 0 1  2 1 0.5  1 0 0  0 1 0  0.3 0.3 0.5 0 0 0 0 0 0 0 0
O  3 0 2  3 1 0.5  1 0 0  0 1 0  0.3 0.3 0.5 0 0 0 0 0 0 0 0
O  4 0 3  3 2 0.5  1 0 0  0 1 0  0.3 0.3 0.5 0 0 0 0 0 0 0 0
O  5 2 4  2 2 3.3  1 0 0  0 1 0  1 1 0.3 0 0 0 0 0 0 0 0
O  6 2 -1  2 2 3.3  1 0 0  0 1 0  1 1 0.3 0 0 0 0 0 0 0 0
"""


def test_house_stats_counts_rooms_floor_area_and_same_category_objects(tmp_path: Path) -> None:
    path = tmp_path / "TOY.house"
    path.write_text(HOUSE)
    stats = house_stats(path)
    assert (stats.name, stats.levels, stats.regions_all, stats.rooms) == ("TOY", 2, 3, 2)
    assert stats.floor_area_m2 == pytest.approx(4 * 3 + 5 * 4)  # the junk region is left out
    assert stats.bbox_area_m2 == pytest.approx(4 * 3 + 5 * 4)
    # wall, "unknown" and the uncategorised object are not target objects
    assert (stats.objects_all, stats.objects) == (7, 4)
    # raw names: chair x2, dining chair, bed -> 3 categories, the two chairs are repeated
    assert (stats.categories_raw, stats.repeated_share_raw) == (3, 0.5)
    assert stats.instances_per_category_raw == pytest.approx(4 / 3, abs=0.01)
    # mpcat40: chair x3, bed -> 2 categories, three of four objects repeated
    assert (stats.categories_mpcat40, stats.repeated_share_mpcat40) == (2, 0.75)


def test_house_stats_names_the_file_and_line_of_a_malformed_record(tmp_path: Path) -> None:
    path = tmp_path / "bad.house"
    path.write_text(HOUSE.replace("0 0 3  5 4 5.5", "0 0 3  five 4 5.5"))
    with pytest.raises(DataFormatError, match=r"bad.house:7: malformed 'R' line"):
        house_stats(path)


def test_the_command_line_reports_a_wrong_header_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "cut.house"
    path.write_text("ASCII 1.\nH  -  -\n")
    assert main(["bench", "mp3d-house", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "first line must be 'ASCII 1.1'" in err


def test_the_command_prints_a_row_per_file_and_their_mean(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    files = [tmp_path / "A.house", tmp_path / "B.house"]
    files[0].write_text(HOUSE)
    files[1].write_text(
        HOUSE.replace("5 4 3  0 0 1", "5 5 3  0 0 1").replace("0 4 3  0 0 1", "0 5 3  0 0 1")
    )
    assert main(["bench", "mp3d-house", *map(str, files)]) == 0
    rows = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [row["name"] for row in rows] == ["A", "B", "mean"]
    assert rows[1]["floor_area_m2"] == pytest.approx(4 * 3 + 5 * 5)
    assert rows[2]["floor_area_m2"] == pytest.approx((32 + 37) / 2)


def _pose(x: float, y: float, z: float) -> list[float]:
    return [1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1]


def test_building_graph_walks_the_navigable_links_and_counts_storeys(tmp_path: Path) -> None:
    # a corridor of three panoramas 3 m apart and a fourth panorama reachable only around a
    # corner: the walk 0 -> 3 is 3 + 4 = 7 m although the straight line is 5 m
    points = [(0, 0), (3, 0), (6, 0), (3, 4)]
    links = {(0, 1), (1, 2), (1, 3)}
    nodes = [
        {
            "image_id": str(i),
            "pose": _pose(x, y, 1.5),
            "included": True,
            "visible": [True] * 4,
            "unobstructed": [(i, j) in links or (j, i) in links for j in range(4)],
            "height": 1.5,
        }
        for i, (x, y) in enumerate(points)
    ]
    path = tmp_path / "toy_connectivity.json"
    path.write_text(json.dumps(nodes))
    graph = building_graph(path)
    walks = sorted([3, 3, 4, 6, 7, 7])  # 0-1, 1-2, 1-3, 0-2, 0-3, 2-3
    assert (graph.name, graph.panoramas, graph.storeys) == ("toy", 4, 1)
    assert graph.mean_path_m == pytest.approx(sum(walks) / 6, abs=0.01)
    assert graph.max_path_m == pytest.approx(7.0)


def test_storeys_ignore_stair_panoramas_and_merge_split_levels() -> None:
    ground, split, stairs, upper = [0.0] * 5, [0.6] * 4, [1.2, 1.9, 2.5], [3.1] * 6
    assert storeys(ground + split + stairs + upper) == 2
    assert storeys(ground) == 1


def test_a_file_that_is_not_a_connectivity_graph_is_reported(tmp_path: Path) -> None:
    path = tmp_path / "x_connectivity.json"
    path.write_text('{"not": "a list"}')
    with pytest.raises(DataFormatError, match="not a Matterport3D Simulator connectivity file"):
        building_graph(path)
