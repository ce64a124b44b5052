"""The exported images: each written once, at the size the prompt shows it.

Each is :func:`vlln.prompt.images.shown_image` of the stored frame, the function the model
agents use at evaluation: level (history and current) views resized to 384x384 and
re-encoded, look-down views copied as stored (640x480). Paths are relative to the export folder, as
LLaVA/Qwen-VL fine-tuning scripts expect (``image_folder`` + path).
"""

from __future__ import annotations

from pathlib import Path

from vlln.datagen.reader import HouseDataset
from vlln.files import ReadCap, writing
from vlln.prompt import ImageRef
from vlln.prompt.images import shown_image

IMAGES_DIR = "images"
# A stored frame is a JPEG of some tens of kB.
_FRAME_CAP = ReadCap("a stored frame", 16)


def image_name(house: str, episode_index: int, ref: ImageRef) -> str:
    """``house`` is the house folder's name, after its dataset's tag where several are mixed."""
    return f"{IMAGES_DIR}/{house}/episode_{episode_index:06d}/{ref.camera}_{ref.frame:06d}.jpg"


class ImageStore:
    """Writes the images samples refer to into ``out``, skipping those already written."""

    def __init__(self, out: Path) -> None:
        self.out = out
        self.written: set[str] = set()

    def add(self, house: HouseDataset, episode_index: int, ref: ImageRef, prefix: str = "") -> str:
        """The image's path relative to ``out`` (under ``prefix``, the dataset's tag and a
        slash where several are mixed); written on first use."""
        name = image_name(prefix + house.root.name, episode_index, ref)
        if name not in self.written:
            source = house.image_file(ref.camera, episode_index, ref.frame)
            data = shown_image(_FRAME_CAP.read(source), ref.camera)
            path = self.out / name
            with writing(path):
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_bytes(data)
            self.written.add(name)
        return name
