"""Statistics of a real Matterport3D ``.house`` file, to anchor our houses against MP3D.

The procedural preset is calibrated against MP3D as VL-LN uses it; where the papers give only
dataset totals, real ``.house`` files give the per-building spread. This module reads the
documented text format (docs/world-statistics.md, "The .house parser") and reduces one file
to the figures the anchors need. Run it as ``vlln bench mp3d-house FILE...``.
"""

from __future__ import annotations

import json
import statistics
from collections import Counter
from dataclasses import asdict, dataclass
from pathlib import Path

from vlln.bench.settings import Mp3dHouseBench
from vlln.errors import DataFormatError
from vlln.world.scans.checks import ANNOTATION_CAP

HEADER = "ASCII 1.1"

# Region labels that are not rooms: "Z" junk and "-" no label (niessner/Matterport
# data_organization.md, region label codes).
NON_ROOM_LABELS = frozenset({"Z", "-"})

# mpcat40 classes that are building structure, not objects a target could be: the room shell
# (wall, floor, ceiling), openings (door, window), structural members (column, beam, railing)
# and the void/unlabeled classes MP3D uses for removed or unannotated geometry.
STRUCTURE_MPCAT40 = frozenset(
    {"void", "wall", "floor", "ceiling", "door", "window", "column", "beam", "railing", "unlabeled"}
)
# Raw category names that say nothing about what the object is (their mpcat40 is misc/objects
# or void, which also holds real objects, so they are dropped by raw name).
UNINFORMATIVE_RAW = frozenset({"unknown", "object", "remove", "delete"})


@dataclass(frozen=True)
class HouseStats:
    """Per-building figures; ``*_share`` are fractions of the kept objects."""

    name: str
    levels: int
    regions_all: int
    rooms: int
    floor_area_m2: float
    bbox_area_m2: float
    objects_all: int
    objects: int
    categories_raw: int
    instances_per_category_raw: float
    repeated_share_raw: float
    categories_mpcat40: int
    instances_per_category_mpcat40: float
    repeated_share_mpcat40: float


def _polygon_area(points: list[tuple[float, float]]) -> float:
    """Shoelace area of a simple polygon given in order (MP3D lists them counter-clockwise)."""
    following = points[1:] + points[:1]
    twice = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, following, strict=True))
    return abs(twice) / 2.0


def _repeated_share(counts: Counter[str]) -> float:
    """Share of instances whose category has at least one other instance in the house."""
    total = sum(counts.values())
    return sum(n for n in counts.values() if n >= 2) / total if total else 0.0


def house_stats(path: Path) -> HouseStats:
    """Read one ``.house`` file; a malformed one raises DataFormatError naming file and line."""
    try:
        lines = ANNOTATION_CAP.read(path).decode("ascii", errors="replace").splitlines()
    except OSError as err:
        raise DataFormatError(
            f"{path}: cannot read ({err.strerror}); give a readable .house file"
        ) from None
    if not lines or lines[0].strip() != HEADER:
        raise DataFormatError(
            f"{path}: first line must be '{HEADER}'; this is not an MP3D .house file"
        )
    levels = 0
    region_label: dict[int, str] = {}
    region_bbox: dict[int, float] = {}
    surface_region: dict[int, int] = {}
    surface_floor: dict[int, bool] = {}
    polygon: dict[int, list[tuple[float, float]]] = {}
    category: dict[int, tuple[str, str]] = {}
    object_category: list[int] = []
    for number, line in enumerate(lines[1:], start=2):
        tokens = line.split()
        if not tokens:
            continue
        try:
            kind = tokens[0]
            if kind == "L":
                levels += 1
            elif kind == "R":
                index = int(tokens[1])
                region_label[index] = tokens[5]
                xlo, ylo, xhi, yhi = (float(tokens[i]) for i in (9, 10, 12, 13))
                region_bbox[index] = (xhi - xlo) * (yhi - ylo)
            elif kind == "S":
                surface_region[int(tokens[1])] = int(tokens[2])
                surface_floor[int(tokens[1])] = tokens[4] == "F"
            elif kind == "V":
                polygon.setdefault(int(tokens[2]), []).append((float(tokens[4]), float(tokens[5])))
            elif kind == "C":
                category[int(tokens[1])] = (tokens[3].replace("#", " "), tokens[5])
            elif kind == "O":
                object_category.append(int(tokens[3]))
        except (IndexError, ValueError):
            raise DataFormatError(
                f"{path}:{number}: malformed '{tokens[0]}' line; see the field list in "
                "docs/world-statistics.md"
            ) from None
    rooms = {i for i, label in region_label.items() if label not in NON_ROOM_LABELS}
    floor_area = sum(
        _polygon_area(points)
        for surface, points in polygon.items()
        if surface_floor.get(surface) and surface_region.get(surface) in rooms and len(points) >= 3
    )
    kept = [
        category[c]
        for c in object_category
        if c in category
        and category[c][1] not in STRUCTURE_MPCAT40
        and category[c][0] not in UNINFORMATIVE_RAW
    ]
    raw, coarse = Counter(name for name, _ in kept), Counter(name for _, name in kept)
    return HouseStats(
        name=path.stem,
        levels=levels,
        regions_all=len(region_label),
        rooms=len(rooms),
        floor_area_m2=round(floor_area, 1),
        bbox_area_m2=round(sum(region_bbox[i] for i in rooms), 1),
        objects_all=len(object_category),
        objects=len(kept),
        categories_raw=len(raw),
        instances_per_category_raw=round(len(kept) / len(raw), 2) if raw else 0.0,
        repeated_share_raw=round(_repeated_share(raw), 3),
        categories_mpcat40=len(coarse),
        instances_per_category_mpcat40=round(len(kept) / len(coarse), 2) if coarse else 0.0,
        repeated_share_mpcat40=round(_repeated_share(coarse), 3),
    )


def run_mp3d_house(settings: Mp3dHouseBench) -> None:
    """Print one JSON line per file, then the mean of each figure when there are several."""
    rows = [house_stats(path) for path in settings.files]
    for row in rows:
        print(json.dumps(asdict(row)))
    if len(rows) > 1:
        numeric = [k for k, v in asdict(rows[0]).items() if isinstance(v, (int, float))]
        mean = {k: round(statistics.mean(getattr(r, k) for r in rows), 3) for k in numeric}
        print(json.dumps({"name": "mean", **mean}))
