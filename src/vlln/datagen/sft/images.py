"""The exported images: each written once, under a name that says which frame it is.

History and current views are the level camera's frames resized to a square (the paper's
384x384), re-encoded as JPEG; look-down images keep their size, so their bytes are copied from
the dataset unchanged and pixel goals stay in the dataset camera's pixels. Paths are relative
to the export folder, as LLaVA/Qwen-VL fine-tuning scripts expect (``image_folder`` + path).
"""

from __future__ import annotations

import io
from pathlib import Path

from PIL import Image

from vlln.datagen.layout import HouseDataset
from vlln.datagen.sft.conversation import DOWN, ImageRef

IMAGES_DIR = "images"


def image_name(house: str, episode_index: int, ref: ImageRef) -> str:
    return f"{IMAGES_DIR}/{house}/episode_{episode_index:06d}/{ref.camera}_{ref.frame:06d}.jpg"


class ImageStore:
    """Writes the images samples refer to into ``out``, skipping those already written."""

    def __init__(self, out: Path, size: int, quality: int) -> None:
        self.out = out
        self.size = size
        self.quality = quality
        self.written: set[str] = set()

    def add(self, house: HouseDataset, episode_index: int, ref: ImageRef) -> str:
        """The image's path relative to ``out``; written on first use."""
        name = image_name(house.root.name, episode_index, ref)
        if name not in self.written:
            source = house.image_file(ref.camera, "rgb", episode_index, ref.frame)
            data = source.read_bytes() if ref.camera == DOWN else self._resized(source)
            path = self.out / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
            self.written.add(name)
        return name

    def _resized(self, source: Path) -> bytes:
        with Image.open(source) as image:
            square = image.convert("RGB").resize((self.size, self.size), Image.Resampling.BICUBIC)
        buffer = io.BytesIO()
        square.save(buffer, "JPEG", quality=self.quality)
        return buffer.getvalue()
