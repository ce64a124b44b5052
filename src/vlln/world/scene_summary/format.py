"""The scene-summary format's file names, numbers and label tables, shared by writer and reader."""

from __future__ import annotations

import numpy as np

from vlln.world.model import Point2

OBJECT_DICT_FILE = "object_dict.json"
REGION_DICT_FILE = "region_dict.json"
DECIMALS = 4  # 0.1 mm
ENLARGE_MARGIN = 0.3  # m; about a wall's thickness plus a doorway's depth
UNKNOWN_ROOM_ID = -1  # room_id of an instance whose room the file does not say

# Our room types and the region labels of the released data (misspellings are the data's).
ROOM_TYPE_TO_LABEL: dict[str, str] = {
    "living room": "living region",
    "bedroom": "resting region",
    "kitchen": "cooking region",
    "dining room": "dinning region",
    "bathroom": "bathing region",
    "toilet": "toliet region",
    "study": "study region",
    "corridor": "corridor region",
    "storage room": "storage region",
    "gym": "sports region",
    "stairs": "stair region",
    "open area": "open area region",
    "other": "other region",
}
LABEL_TO_ROOM_TYPE: dict[str, str] = {label: kind for kind, label in ROOM_TYPE_TO_LABEL.items()}

# How the reference oracle says each region label aloud.
SPOKEN_ROOM_NAMES: dict[str, str] = {
    "living region": "living room",
    "stair region": "stairs",
    "bathing region": "bathroom",
    "storage region": "storage room",
    "study region": "study room",
    "cooking region": "kitchen",
    "sports region": "sports room",
    "corridor region": "corridor",
    "toliet region": "toilet",
    "dinning region": "dining room",
    "resting region": "resting room",
    "open area region": "open area",
    "other region": "area",
}

DESCRIPTION_KEYS = ("color", "texture", "material", "shape", "placement", "size")
FINE_CATEGORY_KEY = "fine grained category"


def grown_polygon(polygon: tuple[Point2, ...], margin: float) -> list[Point2]:
    """``polygon`` with every edge moved ``margin`` outward (mitred corners), either winding."""
    p = np.asarray(polygon, dtype=np.float64)
    edges = np.roll(p, -1, axis=0) - p
    lengths = np.linalg.norm(edges, axis=1, keepdims=True)
    direction = np.divide(edges, lengths, out=np.zeros_like(edges), where=lengths > 0)
    twice_area = float(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))
    outward = 1.0 if twice_area >= 0 else -1.0
    after = outward * np.stack([direction[:, 1], -direction[:, 0]], axis=1)
    before = np.roll(after, 1, axis=0)
    denominator = 1.0 + np.sum(before * after, axis=1, keepdims=True)
    # A hairpin corner (denominator 0) has no finite mitre; it moves along one normal instead.
    mitre = np.divide(before + after, denominator, out=after.copy(), where=denominator > 1e-9)
    grown = p + margin * mitre
    return [(float(x), float(z)) for x, z in grown]
