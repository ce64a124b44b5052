"""Qwen2.5-VL-style models made from scratch, randomly initialised, offline, at a named size.

No weights can be downloaded here, so a model that learns is trained from scratch: this builds
one of the family the trainer and the ``vlln`` agent load, with a byte-level BPE tokenizer (so
any text encodes) that knows Qwen's special tokens and the prompt's own tags, a Qwen2-VL image
processor whose ``max_pixels`` sets the image resolution, and a chat template laid out as
Qwen's. Three sizes (:data:`MODEL_SIZES`):

* ``tiny``: a few units, a few patches per image; tests and ``vlln bench agent``;
* ``small``: the CPU recipe (docs/learning.md); 4.0 M parameters, 112x112 images;
* ``base``: a GPU; 81 M parameters, 224x224 images.

Each folder gets a model card (:mod:`vlln.agents.local.card`) naming its size and resolution.
A real checkpoint (say a local copy of Qwen2.5-VL-3B) loads through the same code path.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from vlln.agents.local.card import ModelCard, write_card
from vlln.agents.local.dependencies import require_model_extra
from vlln.agents.local.encoding import ChatEncoder
from vlln.files import writing
from vlln.prompt.text import (
    CONNECTIVES,
    DIALOG_END,
    DIALOG_START,
    HISTORY_INTRO,
    NAVIGATOR,
    ORACLE,
    SYSTEM_TEXT,
    SYSTEM_TEXT_NO_DIALOG,
)

SPECIAL_TOKENS = (
    "<|endoftext|>",
    "<|im_start|>",
    "<|im_end|>",
    "<|vision_start|>",
    "<|vision_end|>",
    "<|image_pad|>",
    "<|video_pad|>",
)
# The prompt's tags, single tokens as in the fine-tuned reference model.
PROMPT_TOKENS = (DIALOG_START, DIALOG_END, NAVIGATOR, ORACLE)

# Qwen's layout: a default system turn, one ``<|im_start|>role\n ... <|im_end|>\n`` block per
# message, each image as ``<|vision_start|><|image_pad|><|vision_end|>``.
CHAT_TEMPLATE = (
    "{% for message in messages %}"
    "{% if loop.first and message['role'] != 'system' %}"
    "<|im_start|>system\nYou are a helpful assistant.<|im_end|>\n{% endif %}"
    "<|im_start|>{{ message['role'] }}\n"
    "{% if message['content'] is string %}{{ message['content'] }}"
    "{% else %}{% for part in message['content'] %}"
    "{% if part['type'] == 'image' %}<|vision_start|><|image_pad|><|vision_end|>"
    "{% elif part['type'] == 'text' %}{{ part['text'] }}{% endif %}"
    "{% endfor %}{% endif %}<|im_end|>\n"
    "{% endfor %}"
    "{% if add_generation_prompt %}<|im_start|>assistant\n{% endif %}"
)

# Text the BPE merges are learnt from: the prompt's own sentences, so samples stay short.
_CORPUS = (
    SYSTEM_TEXT,
    SYSTEM_TEXT_NO_DIALOG,
    HISTORY_INTRO,
    " ".join(CONNECTIVES),
    "search for the chair bed sofa table lamp basket plant. You are an autonomous navigation "
    "assistant. In front of you is <image>. Locate the goal location on the floor. <talk>"
    "Which room is it in? Is it the one near the window? Yes. No. It is made of plastic. "
    "<move>←←→→↑↓ <move>STOP <move>320 240 system user assistant You are a helpful assistant.",
    " ".join(str(number) for number in range(0, 640, 7)),
)


def is_model_file(path: Path) -> bool:
    """Whether ``path`` is a file :func:`build_model` writes (weights, configurations,
    tokenizer, chat template, card), so that a rerun may replace its folder."""
    return path.is_file() and path.suffix in (".json", ".safetensors", ".jinja")


SizeName = Literal["tiny", "small", "base"]


@dataclass(frozen=True)
class ModelSize:
    """A model's shape: language model layers and width, vision tower, image resolution."""

    hidden: int
    layers: int
    heads: int
    vision_hidden: int
    vision_depth: int
    vision_heads: int
    max_pixels: int  # pixels of each image after the processor's resize
    window: int = 112  # pixels on a side of the vision tower's attention windows

    def text_config(self, vocab_size: int) -> dict[str, Any]:
        head_dim = self.hidden // self.heads
        eighth = head_dim // 8  # Qwen's split of the rotary half: 1/4 time, 3/8 height, 3/8 width
        height = (head_dim // 2 - eighth) // 2
        return {
            "hidden_size": self.hidden,
            "intermediate_size": 2 * self.hidden,
            "num_hidden_layers": self.layers,
            "num_attention_heads": self.heads,
            "num_key_value_heads": max(1, self.heads // 2),
            "max_position_embeddings": 4096,
            "vocab_size": vocab_size,
            "rope_parameters": {
                "rope_type": "default",
                "mrope_section": [eighth, height, head_dim // 2 - eighth - height],
            },
        }

    def vision_config(self) -> dict[str, Any]:
        return {
            "depth": self.vision_depth,
            "hidden_size": self.vision_hidden,
            "intermediate_size": 2 * self.vision_hidden,
            "num_heads": self.vision_heads,
            "out_hidden_size": self.hidden,
            "patch_size": 14,
            "spatial_merge_size": 2,
            "temporal_patch_size": 2,
            "window_size": self.window,
            "fullatt_block_indexes": [self.vision_depth - 1],
        }


MODEL_SIZES: dict[str, ModelSize] = {
    "tiny": ModelSize(64, 2, 4, 32, 2, 2, max_pixels=56 * 56, window=56),
    "small": ModelSize(256, 4, 4, 128, 4, 4, max_pixels=112 * 112),
    "base": ModelSize(768, 12, 12, 384, 8, 6, max_pixels=224 * 224),
}


def build_model(out_dir: str | Path, size: str = "tiny", seed: int = 0) -> Path:
    """Write a randomly initialised model of ``size``, its processor, chat template and card
    to ``out_dir``."""
    require_model_extra()
    from transformers import Qwen2VLImageProcessorPil

    shape = MODEL_SIZES[size]
    tokenizer = local_tokenizer()
    image_processor = Qwen2VLImageProcessorPil(
        min_pixels=28 * 28, max_pixels=shape.max_pixels, patch_size=14, merge_size=2
    )
    text = shape.text_config(len(tokenizer))
    out = write_random_model(out_dir, tokenizer, image_processor, text, shape.vision_config(), seed)
    write_card(out, ModelCard(size=size, image_max_pixels=shape.max_pixels))
    return out


def build_tiny_model(out_dir: str | Path, seed: int = 0) -> Path:
    """The ``tiny`` model of :func:`build_model` (tests and benchmarks)."""
    return build_model(out_dir, "tiny", seed)


def local_tokenizer() -> Any:
    """A byte-level BPE tokenizer learnt here from the prompt's sentences, knowing Qwen's
    special tokens and the prompt's tags (module doc)."""
    from tokenizers import Tokenizer, decoders, models, pre_tokenizers, trainers
    from transformers import PreTrainedTokenizerFast

    backend = Tokenizer(models.BPE())
    backend.pre_tokenizer = pre_tokenizers.ByteLevel(add_prefix_space=False)
    backend.decoder = decoders.ByteLevel()
    trainer = trainers.BpeTrainer(
        vocab_size=1000,
        special_tokens=list(SPECIAL_TOKENS + PROMPT_TOKENS),
        initial_alphabet=pre_tokenizers.ByteLevel.alphabet(),
        show_progress=False,
    )
    backend.train_from_iterator(_CORPUS, trainer=trainer)
    return PreTrainedTokenizerFast(
        tokenizer_object=backend,
        eos_token="<|im_end|>",
        pad_token="<|endoftext|>",
        additional_special_tokens=list(SPECIAL_TOKENS[1:] + PROMPT_TOKENS),
    )


def write_random_model(
    out_dir: str | Path,
    tokenizer: Any,
    image_processor: Any,
    text_config: dict[str, Any],
    vision_config: dict[str, Any],
    seed: int = 0,
    device: str = "cpu",
    dtype: Any = None,
) -> Path:
    """A Qwen2.5-VL of the given text and vision configuration with weights drawn from
    ``seed`` (made on ``device`` in ``dtype``, float32 by default), its special tokens those
    of ``tokenizer``, saved to ``out_dir`` with the tokenizer, image processor and template."""
    import torch
    from transformers import Qwen2_5_VLConfig, Qwen2_5_VLForConditionalGeneration

    vocabulary = tokenizer.get_vocab()
    ids = {token: vocabulary[token] for token in SPECIAL_TOKENS}
    text = text_config | {
        "bos_token_id": ids["<|endoftext|>"],
        "eos_token_id": ids["<|im_end|>"],
        "pad_token_id": ids["<|endoftext|>"],
    }
    config = Qwen2_5_VLConfig(
        text_config=text,
        vision_config=vision_config,
        image_token_id=ids["<|image_pad|>"],
        video_token_id=ids["<|video_pad|>"],
        vision_start_token_id=ids["<|vision_start|>"],
        vision_end_token_id=ids["<|vision_end|>"],
        tie_word_embeddings=bool(text.get("tie_word_embeddings", False)),
    )
    torch.manual_seed(seed)
    default_dtype = torch.get_default_dtype()
    torch.set_default_dtype(dtype or torch.float32)
    try:
        with torch.device(device):
            model = Qwen2_5_VLForConditionalGeneration(config)
    finally:
        torch.set_default_dtype(default_dtype)
    model.generation_config.eos_token_id = ids["<|im_end|>"]
    model.generation_config.pad_token_id = ids["<|endoftext|>"]
    out = Path(out_dir)
    with writing(out):
        out.mkdir(parents=True, exist_ok=True)
        model.save_pretrained(out)
        ChatEncoder(tokenizer, image_processor, CHAT_TEMPLATE).save(out)
    return out
