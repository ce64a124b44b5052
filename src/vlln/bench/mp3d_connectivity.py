"""Storeys and walking distances of all 90 MP3D buildings, from the R2R connectivity graphs.

The ``.house`` files themselves are licence-restricted, but the Matterport3D Simulator publishes
one connectivity graph per building (``connectivity/<scan>_connectivity.json``: panorama poses,
camera height above the floor, navigable transitions; MIT licence). From them we get, for every
building VL-LN uses, the number of storeys and the distribution of walking distances between
navigable places, which anchor our preset where the papers give no per-building figures.
Run it as ``vlln bench mp3d-connectivity FILE...``.
"""

from __future__ import annotations

import json
import statistics
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import shortest_path

from vlln.bench.settings import Mp3dConnectivityBench
from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json

# Panoramas of one floor lie within a few centimetres of the same floor height; stair panoramas
# sit alone at heights in between. Heights closer than FLOOR_GAP_M form one floor, a floor needs
# MIN_PANORAMAS_PER_FLOOR panoramas (which drops the stairs), and floors less than
# STOREY_HEIGHT_M above the lowest floor of the current storey are split levels of that storey.
FLOOR_GAP_M = 0.3
MIN_PANORAMAS_PER_FLOOR = 3
STOREY_HEIGHT_M = 1.5
# The largest building's graph (a few hundred panoramas, each listing all the others) is a few MB.
CONNECTIVITY_CAP = ReadCap("a connectivity file", 16)


@dataclass(frozen=True)
class BuildingGraph:
    """Per-building figures: storeys, panoramas, and graph walking distances in metres."""

    name: str
    panoramas: int
    storeys: int
    mean_path_m: float
    median_path_m: float
    p90_path_m: float
    max_path_m: float


def storeys(floor_z: list[float]) -> int:
    """Count storeys from the floor heights under the panoramas of one building."""
    floors: list[list[float]] = []
    for z in sorted(floor_z):
        if floors and z - floors[-1][-1] < FLOOR_GAP_M:
            floors[-1].append(z)
        else:
            floors.append([z])
    levels = [statistics.median(f) for f in floors if len(f) >= MIN_PANORAMAS_PER_FLOOR]
    count, base = 0, float("-inf")
    for level in levels:
        if level - base >= STOREY_HEIGHT_M:
            count, base = count + 1, level
    return max(1, count)


def building_graph(path: Path) -> BuildingGraph:
    """Read one connectivity file; walking distance = shortest path over navigable transitions."""
    try:
        data = CONNECTIVITY_CAP.read(path)
    except OSError as err:
        raise DataFormatError(
            f"{path}: cannot read ({err.strerror}); give connectivity/<scan>_connectivity.json"
        ) from None
    try:
        nodes = parse_json(data)
        included = [i for i, node in enumerate(nodes) if node["included"]]
        position = np.array([[nodes[i]["pose"][k] for k in (3, 7, 11)] for i in included])
        floor_z = [float(nodes[i]["pose"][11] - nodes[i]["height"]) for i in included]
        links = [
            (a, b)
            for a, i in enumerate(included)
            for b, j in enumerate(included)
            if a < b and nodes[i]["unobstructed"][j]
        ]
    except (ValueError, KeyError, IndexError, TypeError) as err:
        raise DataFormatError(
            f"{path}: not a Matterport3D Simulator connectivity file ({err!r}); give "
            "connectivity/<scan>_connectivity.json"
        ) from None
    if len(included) < 2 or not links:
        raise DataFormatError(f"{path}: fewer than two connected panoramas; nothing to measure")
    rows, cols = np.array(links).T
    lengths = np.linalg.norm(position[rows] - position[cols], axis=1)
    graph = csr_matrix((lengths, (rows, cols)), shape=(len(included), len(included)))
    distance = shortest_path(graph, directed=False)
    pairs = distance[np.triu_indices(len(included), k=1)]
    pairs = pairs[np.isfinite(pairs)]
    return BuildingGraph(
        name=path.name.removesuffix("_connectivity.json"),
        panoramas=len(included),
        storeys=storeys(floor_z),
        mean_path_m=round(float(pairs.mean()), 2),
        median_path_m=round(float(np.median(pairs)), 2),
        p90_path_m=round(float(np.percentile(pairs, 90)), 2),
        max_path_m=round(float(pairs.max()), 2),
    )


def run_mp3d_connectivity(settings: Mp3dConnectivityBench) -> None:
    """Print one JSON line per building, then the mean of each figure and the storey counts."""
    rows = [building_graph(path) for path in settings.files]
    for row in rows:
        print(json.dumps(asdict(row)))
    numeric = [k for k, v in asdict(rows[0]).items() if isinstance(v, (int, float))]
    summary = {k: round(statistics.mean(getattr(r, k) for r in rows), 3) for k in numeric}
    counts = {n: sum(r.storeys == n for r in rows) for n in sorted({r.storeys for r in rows})}
    print(json.dumps({"name": "mean", "buildings": len(rows), **summary, "storey_counts": counts}))
