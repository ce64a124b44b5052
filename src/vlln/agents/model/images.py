"""The pictures a model agent shows its model, prepared as the training data store them.

Training frames are saved as JPEG (quality 90) at the camera's 640x480; the export shows the
level ones resized to 384x384 (bicubic) and re-encoded, the look-down one as saved. The agent
repeats those steps so that a fine-tuned model sees at evaluation the pixels it was trained
on; keeping the level frames as JPEG bytes also bounds an episode's memory (about 25 kB a
frame instead of 430 kB).
"""

from __future__ import annotations

import io

import numpy as np
from numpy.typing import NDArray
from PIL import Image

from vlln.prompt import DOWN_IMAGE_SIZE, LEVEL_IMAGE_SIZE

JPEG_QUALITY = 90  # the training data's quality (vlln.datagen.layout)


def _jpeg(image: Image.Image) -> bytes:
    buffer = io.BytesIO()
    image.save(buffer, "JPEG", quality=JPEG_QUALITY)
    return buffer.getvalue()


def level_image(rgb: NDArray[np.uint8]) -> bytes:
    """A level frame as the model sees it: saved as JPEG, resized to 384x384, re-encoded."""
    saved = Image.open(io.BytesIO(_jpeg(Image.fromarray(rgb))))
    return _jpeg(saved.convert("RGB").resize(LEVEL_IMAGE_SIZE, Image.Resampling.BICUBIC))


def down_image(rgb: NDArray[np.uint8]) -> bytes:
    """The look-down frame as the model sees it: JPEG at the camera's 640x480."""
    image = Image.fromarray(rgb)
    if image.size != DOWN_IMAGE_SIZE:
        image = image.resize(DOWN_IMAGE_SIZE, Image.Resampling.BICUBIC)
    return _jpeg(image)
