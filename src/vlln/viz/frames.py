"""Turn depth and instance-id images into pictures a person can read."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib import colormaps
from numpy.typing import NDArray
from PIL import Image

from vlln.files import writing
from vlln.world.model import StructureId

_STRUCTURE_COLORS = {
    int(StructureId.NOTHING): (0, 0, 0),
    int(StructureId.FLOOR): (90, 90, 90),
    int(StructureId.WALL): (150, 150, 150),
    int(StructureId.CEILING): (200, 200, 200),
    int(StructureId.DOOR_FRAME): (120, 100, 80),
}


def depth_image(depth: NDArray[np.float32], max_depth: float = 10.0) -> NDArray[np.uint8]:
    """Depth in metres as an RGB image (near = bright, far = dark; 0 = no reading = black)."""
    scaled = np.clip(depth / max_depth, 0.0, 1.0)
    rgb = colormaps["magma_r"](scaled)[..., :3]
    rgb[depth <= 0] = 0.0
    return (rgb * 255).astype(np.uint8)


def instance_color(instance_id: int) -> tuple[int, int, int]:
    """A stable, well-spread colour per object id; structure gets fixed greys."""
    if instance_id in _STRUCTURE_COLORS:
        return _STRUCTURE_COLORS[instance_id]
    h = (instance_id * 2654435761) & 0xFFFFFFFF
    return (64 + (h & 0xBF), 64 + ((h >> 8) & 0xBF), 64 + ((h >> 16) & 0xBF))


def instance_image(ids: NDArray[np.int32]) -> NDArray[np.uint8]:
    """Instance ids as an RGB image, one colour per id."""
    unique, inverse = np.unique(ids, return_inverse=True)
    palette = np.array([instance_color(int(i)) for i in unique], np.uint8)
    return palette[inverse.reshape(ids.shape)]


def save_png(image: NDArray[np.uint8], path: Path) -> None:
    """Write ``image`` as a PNG; a full disk or a read-only folder is one WriteError line."""
    with writing(path):
        path.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(image).save(path)
