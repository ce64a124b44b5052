"""Conversations with ``<image>`` tags turned into the token and pixel tensors of a
Qwen-VL-style model, one path for training and for the ``vlln`` agent.

A conversation is a sequence of :class:`vlln.prompt.Turn` (role ``"human"`` or ``"gpt"``),
as the training export writes them and the agents build them. Each ``<image>`` tag becomes an
image part of the message, which the model's chat template renders as
``<|vision_start|><|image_pad|><|vision_end|>``; the single ``<|image_pad|>`` is then repeated
once per merged vision patch of its image, as Qwen's processors do. (The processor classes
themselves also need torchvision for video, which this project does not install, so the two
steps are done here with the model's own tokenizer, image processor and chat template.)
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from itertools import accumulate
from pathlib import Path
from typing import TYPE_CHECKING, Any

from vlln.errors import ConfigError, DataFormatError
from vlln.files import ReadCap, parse_json
from vlln.prompt import IMAGE_TAG, Turn

if TYPE_CHECKING:
    import torch
    from PIL.Image import Image

IGNORE_INDEX = -100  # label of every token the loss skips
IMAGE_PAD = "<|image_pad|>"
ASSISTANT_HEADER = "<|im_start|>assistant\n"
END_OF_TURN = "<|im_end|>"
_ROLES = {"human": "user", "gpt": "assistant"}
# Qwen-VL chat templates are a few KB of Jinja.
CHAT_TEMPLATE_CAP = ReadCap("a chat template", 1)

Turns = Sequence[Turn]


def to_messages(turns: Turns) -> list[dict[str, Any]]:
    """Chat-template messages: in user turns each ``<image>`` tag becomes an image part, in
    place; assistant turns (which show no images) stay plain strings, the form every Qwen-VL
    template renders the same way."""
    messages: list[dict[str, Any]] = []
    for turn in turns:
        role = _ROLES.get(turn.role)
        if role is None:
            raise ConfigError(f"a turn's role must be 'human' or 'gpt', got {turn.role!r}")
        if role == "assistant":
            messages.append({"role": role, "content": turn.text})
            continue
        parts: list[dict[str, Any]] = []
        for index, piece in enumerate(turn.text.split(IMAGE_TAG)):
            if index:
                parts.append({"type": "image"})
            if piece:
                parts.append({"type": "text", "text": piece})
        messages.append({"role": role, "content": parts})
    return messages


@dataclass(frozen=True)
class ProcessedImage:
    """One image as the model's image processor gives it: its patch rows and (t, h, w) grid."""

    pixels: torch.Tensor
    grid: torch.Tensor

    @property
    def nbytes(self) -> int:
        return int(self.pixels.element_size() * self.pixels.nelement())


class ChatEncoder:
    """The tokenizer, image processor and chat template of one model directory."""

    def __init__(self, tokenizer: Any, image_processor: Any, chat_template: str) -> None:
        self.tokenizer = tokenizer
        self.image_processor = image_processor
        self.chat_template = chat_template
        self.image_token_id = _token_id(tokenizer, IMAGE_PAD)
        self.end_of_turn_id = _token_id(tokenizer, END_OF_TURN)
        self.assistant_header = tokenizer.encode(ASSISTANT_HEADER, add_special_tokens=False)
        self.merge_area = int(image_processor.merge_size) ** 2

    @classmethod
    def load(cls, model_dir: str | Path, max_pixels: int | None = None) -> ChatEncoder:
        """``max_pixels`` caps the pixels of every image (fewer vision tokens)."""
        saved = _saved_template(Path(model_dir))  # first: the tokenizer's loader reads it whole
        from transformers import AutoImageProcessor, AutoTokenizer

        options = {} if max_pixels is None else {"max_pixels": max_pixels}
        with model_loading(model_dir):
            tokenizer = AutoTokenizer.from_pretrained(model_dir)
            image_processor = AutoImageProcessor.from_pretrained(model_dir, **options)
        template = getattr(tokenizer, "chat_template", None) or saved
        if not template:
            raise ConfigError(
                f"{model_dir} has no chat template (tokenizer_config.json, chat_template.jinja or "
                "chat_template.json); use a Qwen-VL instruct checkpoint or one saved by vlln "
                "train sft"
            )
        return cls(tokenizer, image_processor, str(template))

    def save(self, out_dir: str | Path) -> None:
        """Write the tokenizer, image processor and template beside a saved model."""
        self.tokenizer.chat_template = self.chat_template
        self.tokenizer.save_pretrained(out_dir)
        self.image_processor.save_pretrained(out_dir)

    def render(self, turns: Turns, add_generation_prompt: bool) -> str:
        text: str = self.tokenizer.apply_chat_template(
            to_messages(turns),
            chat_template=self.chat_template,
            tokenize=False,
            add_generation_prompt=add_generation_prompt,
        )
        return text

    def process_images(self, images: Sequence[Image]) -> list[ProcessedImage]:
        """Each image as the model's image processor turns it into patches (it treats every
        image on its own, so processing them apart or together gives the same tensors)."""
        if not images:
            return []
        features = self.image_processor(images=list(images), return_tensors="pt")
        grids = features["image_grid_thw"]
        rows = features["pixel_values"].split([int(grid.prod()) for grid in grids])
        return [ProcessedImage(pixels, grid) for pixels, grid in zip(rows, grids, strict=True)]

    def encode(
        self,
        texts: Sequence[str],
        images: Sequence[Sequence[Image]],
        padding_side: str = "right",
    ) -> dict[str, torch.Tensor]:
        """A padded batch: ``texts[i]`` holds one ``<|image_pad|>`` per image of ``images[i]``."""
        flat = self.process_images([image for group in images for image in group])
        ends = list(accumulate(len(group) for group in images))
        groups = [flat[end - len(group) : end] for group, end in zip(images, ends, strict=True)]
        return self.encode_processed(texts, groups, padding_side)

    def encode_processed(
        self,
        texts: Sequence[str],
        images: Sequence[Sequence[ProcessedImage]],
        padding_side: str = "right",
    ) -> dict[str, torch.Tensor]:
        """:meth:`encode` of images already through :meth:`process_images` (a training run
        processes each frame once, not once per sample that shows it)."""
        import torch

        expanded: list[str] = []
        for text, group in zip(texts, images, strict=True):
            pieces = text.split(IMAGE_PAD)
            if len(pieces) - 1 != len(group):
                raise ConfigError(
                    f"a conversation has {len(pieces) - 1} image placeholders but "
                    f"{len(group)} images; every <image> tag needs exactly one image"
                )
            out = pieces[0]
            for piece, image in zip(pieces[1:], group, strict=True):
                out += IMAGE_PAD * (int(image.grid.prod()) // self.merge_area) + piece
            expanded.append(out)
        tokens = self.tokenizer(
            expanded,
            padding=True,
            padding_side=padding_side,
            add_special_tokens=False,
            return_tensors="pt",
        )
        batch = {"input_ids": tokens["input_ids"], "attention_mask": tokens["attention_mask"]}
        batch["mm_token_type_ids"] = (batch["input_ids"] == self.image_token_id).int()
        flat = [image for group in images for image in group]
        if flat:
            batch["pixel_values"] = torch.cat([image.pixels for image in flat])
            batch["image_grid_thw"] = torch.stack([image.grid for image in flat])
        return batch

    def assistant_labels(
        self, input_ids: torch.Tensor, attention_mask: torch.Tensor
    ) -> torch.Tensor:
        """Labels that keep only the assistant's tokens (its text and closing ``<|im_end|>``);
        the system and user turns, images, role headers and padding are ``IGNORE_INDEX``."""
        labels = input_ids.clone().fill_(IGNORE_INDEX)
        header = self.assistant_header
        for row, ids in enumerate(input_ids.tolist()):
            inside = False
            position = 0
            while position < len(ids):
                if not inside and ids[position : position + len(header)] == header:
                    inside = True
                    position += len(header)
                    continue
                if inside:
                    labels[row, position] = ids[position]
                    inside = ids[position] != self.end_of_turn_id
                position += 1
        return labels.masked_fill(attention_mask == 0, IGNORE_INDEX)


@contextmanager
def model_loading(model: str | Path) -> Iterator[None]:
    """Turns the loaders' errors for a missing or unreadable model into one clear line."""
    try:
        yield
    except (OSError, ValueError) as error:
        first_line = str(error).strip().splitlines()[0] if str(error).strip() else ""
        raise ConfigError(
            f"cannot load the model {str(model)!r} ({first_line}); pass a model folder "
            "(the --out of vlln train sft) or a Hugging Face name available on this machine"
        ) from error


def _token_id(tokenizer: Any, token: str) -> int:
    token_id = tokenizer.convert_tokens_to_ids(token)
    if token_id is None or token_id == tokenizer.unk_token_id:
        raise ConfigError(
            f"the model's tokenizer has no {token} token; vlln supports Qwen2-VL, Qwen2.5-VL "
            "and Qwen3-VL style models"
        )
    return int(token_id)


def _saved_template(model_dir: Path) -> str | None:
    """The chat template saved beside a model's tokenizer (``chat_template.jinja``) or
    processor (``chat_template.json``), if any."""
    for name in ("chat_template.jinja", "chat_template.json"):
        if (model_dir / name).is_file():
            return _template_file(model_dir / name)
    return None


def _template_file(path: Path) -> str:
    """A ``.jinja`` template, or a ``.json`` one holding it as ``chat_template``: untrusted, as
    a model folder may come from anywhere, so read to :data:`CHAT_TEMPLATE_CAP`."""
    data = CHAT_TEMPLATE_CAP.read(path)
    try:
        if path.suffix == ".jinja":
            return data.decode("utf-8")
        template = parse_json(data)["chat_template"]
        if not isinstance(template, str):
            raise TypeError("its chat_template is not text")
        return template
    except (UnicodeDecodeError, DataFormatError, KeyError, TypeError) as error:
        raise DataFormatError(
            f"{path} is not a chat template ({error}); use a Qwen-VL instruct checkpoint or "
            "one saved by vlln train sft"
        ) from None
