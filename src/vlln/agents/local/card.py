"""The model card: what a model folder was made or trained with, stated once beside its
weights, so that evaluation reads it instead of being told again.

``vlln train new-model`` writes it for a model made from scratch and ``vlln train sft`` for
the model it trains (the history length of its export, the houses its data came from); the
``vlln`` agent builds its prompts with the card's history length, and ``vlln eval`` warns
when it scores a model on other houses than it was trained on. The image resolution is the
image processor's ``max_pixels`` (``preprocessor_config.json``, which the encoder reads); the
card repeats it for people only. A folder without a card (a downloaded Qwen-VL checkpoint)
reads as the reference's prompt: 8 history frames, houses unknown.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

from pydantic import Field

from vlln.config import Config
from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, write_text_atomic
from vlln.prompt import DEFAULT_HISTORY_COUNT

CARD_FILE = "vlln_model.json"
# A card is five short settings: a few hundred bytes.
_CARD_CAP = ReadCap("a model card", 1)


class ModelCard(Config):
    """How a model folder's model sees the benchmark."""

    size: str | None = None
    """the named size it was made at from scratch (none: a checkpoint from elsewhere)"""
    history_frames: Annotated[int, Field(ge=1)] = DEFAULT_HISTORY_COUNT
    """history frames in each prompt it was trained with"""
    image_max_pixels: Annotated[int | None, Field(ge=1)] = None
    """pixels of each image after the processor's resize (the processor's own setting)"""
    houses: str | None = None
    """the house preset of its training data (none: not trained by vlln)"""
    trained_steps: Annotated[int, Field(ge=0)] = 0
    """optimizer steps of vlln train sft behind it"""


def read_card(model_dir: str | Path) -> ModelCard:
    """The card of ``model_dir``; the defaults when it has none."""
    path = Path(model_dir) / CARD_FILE
    if not path.is_file():
        return ModelCard()
    data = _CARD_CAP.read(path)
    try:
        document = parse_json(data)
    except DataFormatError as error:
        raise DataFormatError(f"{path}: {error}; delete it or re-save the model") from None
    return ModelCard.from_json(document, str(path))


def write_card(model_dir: str | Path, card: ModelCard) -> Path:
    """Write ``card`` into ``model_dir``."""
    path = Path(model_dir) / CARD_FILE
    write_text_atomic(path, json.dumps(card.to_json(), indent=2) + "\n")
    return path
