"""The pictures a navigation model is shown: one contract for the data set, the training
export and every model agent, so that a fine-tuned model sees at evaluation the very bytes it
was trained on.

A rendered frame is stored as JPEG with Pillow's "web_low" quantisation tables and optimised
Huffman tables (:func:`stored_frame`; docs/data-pipeline.md gives the reasons and figures).
The model is shown each stored frame at the size its prompt calls for (:func:`shown_image`):
the look-down frame as stored (640x480), level frames decoded, resized to 384x384 (bicubic)
and re-encoded at quality 90. An agent keeps its level frames as these JPEG bytes, which also
bounds an episode's memory (about 25 kB a frame instead of 430 kB).
"""

from __future__ import annotations

import io

import numpy as np
from numpy.typing import NDArray
from PIL import Image

from vlln.files import open_image
from vlln.prompt.conversation import Camera
from vlln.prompt.text import DOWN_IMAGE_SIZE, LEVEL_IMAGE_SIZE

# The reference saves its frames with PIL's default quality (75). Our renders' fine floor
# textures are noise a JPEG cannot compress, so a kept trajectory of the data benchmark takes
# 11.4 MB at 75 and 7.2 MB at 50 (about 0.9 MB of it the 4 KB disk blocks of its ~460 small
# files). Pillow's "web_low" tables quantise the low frequencies a little more and the highest
# ones much less than the standard tables do, which on these frames gives smaller files at a
# higher PSNR than quality 33 (the standard setting of the same size, which blurs the floor
# texture and blotches the colour of plain walls); see docs/data-pipeline.md for the figures.
FRAME_QTABLES = "web_low"  # how the data set stores rendered frames
SHOWN_QUALITY = 90  # how a frame resized for the prompt is re-encoded
_SIZES: dict[Camera, tuple[int, int]] = {"level": LEVEL_IMAGE_SIZE, "down": DOWN_IMAGE_SIZE}


def stored_frame(rgb: NDArray[np.uint8]) -> bytes:
    """A rendered frame as the trajectory data set stores it."""
    buffer = io.BytesIO()
    Image.fromarray(rgb).save(buffer, "JPEG", qtables=FRAME_QTABLES, optimize=True)
    return buffer.getvalue()


def shown_image(stored: bytes, camera: Camera) -> bytes:
    """The JPEG the model is shown for a stored frame of ``camera``: the stored bytes when
    they already have the prompt's size, else resized and re-encoded."""
    size = _SIZES[camera]
    with open_image(stored, f"a stored {camera} frame") as image:
        if image.size == size and image.format == "JPEG":
            return stored
        resized = image.convert("RGB").resize(size, Image.Resampling.BICUBIC)
    buffer = io.BytesIO()
    resized.save(buffer, "JPEG", quality=SHOWN_QUALITY)
    return buffer.getvalue()


def model_image(rgb: NDArray[np.uint8], camera: Camera) -> bytes:
    """The JPEG the model is shown for a frame rendered now, byte for byte what the training
    export holds for the same frame."""
    return shown_image(stored_frame(rgb), camera)
