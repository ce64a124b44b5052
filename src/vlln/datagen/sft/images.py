"""The exported images: each written once, at the size the prompt shows it.

Level (history and current) views are resized to ``LEVEL_IMAGE_SIZE`` (384x384) and
re-encoded; look-down views are ``DOWN_IMAGE_SIZE`` (640x480), their bytes copied when the
dataset's camera already has that size. Paths are relative to the export folder, as
LLaVA/Qwen-VL fine-tuning scripts expect (``image_folder`` + path).
"""

from __future__ import annotations

import io
from pathlib import Path

from PIL import Image

from vlln.datagen.reader import HouseDataset
from vlln.prompt import DOWN_IMAGE_SIZE, LEVEL_IMAGE_SIZE, ImageRef

IMAGES_DIR = "images"


def image_name(house: str, episode_index: int, ref: ImageRef) -> str:
    return f"{IMAGES_DIR}/{house}/episode_{episode_index:06d}/{ref.camera}_{ref.frame:06d}.jpg"


class ImageStore:
    """Writes the images samples refer to into ``out``, skipping those already written."""

    def __init__(self, out: Path, quality: int) -> None:
        self.out = out
        self.quality = quality
        self.written: set[str] = set()

    def add(self, house: HouseDataset, episode_index: int, ref: ImageRef) -> str:
        """The image's path relative to ``out``; written on first use."""
        name = image_name(house.root.name, episode_index, ref)
        if name not in self.written:
            source = house.image_file(ref.camera, episode_index, ref.frame)
            size = LEVEL_IMAGE_SIZE if ref.camera == "level" else DOWN_IMAGE_SIZE
            path = self.out / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(self._sized(source, size))
            self.written.add(name)
        return name

    def _sized(self, source: Path, size: tuple[int, int]) -> bytes:
        with Image.open(source) as image:
            if image.size == size and image.format == "JPEG":
                return source.read_bytes()
            resized = image.convert("RGB").resize(size, Image.Resampling.BICUBIC)
        buffer = io.BytesIO()
        resized.save(buffer, "JPEG", quality=self.quality)
        return buffer.getvalue()
