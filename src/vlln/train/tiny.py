"""A tiny randomly initialised Qwen2.5-VL-style model and processor, built offline.

Tests, ``vlln bench agent`` and ``vlln train tiny-model`` (a user's CPU trial of the pipeline)
need a real model of the family the trainer and the ``vlln`` agent target, and no weights can
be downloaded: this builds one from a small config, with a
byte-level BPE tokenizer (so any text encodes) that knows Qwen's special tokens and the
prompt's own tags, a Qwen2-VL image processor that shrinks every image to a few patches, and
a chat template laid out as Qwen's.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from vlln.agents.local.dependencies import require_model_extra
from vlln.agents.local.encoding import ChatEncoder
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


def is_tiny_model_file(path: Path) -> bool:
    """Whether ``path`` is a file :func:`build_tiny_model` writes (weights, configurations,
    tokenizer, chat template), so that a rerun may replace its folder."""
    return path.is_file() and path.suffix in (".json", ".safetensors", ".jinja")


# The tiny model's architecture: a few layers of a few units, every image a few patches.
TINY_TEXT = {
    "hidden_size": 64,
    "intermediate_size": 128,
    "num_hidden_layers": 2,
    "num_attention_heads": 4,
    "num_key_value_heads": 2,
    "max_position_embeddings": 4096,
    "rope_parameters": {"rope_type": "default", "mrope_section": [2, 3, 3]},
}
TINY_VISION = {
    "depth": 2,
    "hidden_size": 32,
    "intermediate_size": 64,
    "num_heads": 2,
    "out_hidden_size": 64,
    "patch_size": 14,
    "spatial_merge_size": 2,
    "temporal_patch_size": 2,
    "window_size": 56,
    "fullatt_block_indexes": [1],
}


def build_tiny_model(out_dir: str | Path, seed: int = 0, max_pixels: int = 56 * 56) -> Path:
    """Write a tiny Qwen2.5-VL model, its processor and chat template to ``out_dir``."""
    require_model_extra()
    from transformers import Qwen2VLImageProcessorPil

    tokenizer = local_tokenizer()
    image_processor = Qwen2VLImageProcessorPil(
        min_pixels=28 * 28, max_pixels=max_pixels, patch_size=14, merge_size=2
    )
    text = TINY_TEXT | {"vocab_size": len(tokenizer)}
    return write_random_model(out_dir, tokenizer, image_processor, text, TINY_VISION, seed)


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
    out.mkdir(parents=True, exist_ok=True)
    model.save_pretrained(out)
    ChatEncoder(tokenizer, image_processor, CHAT_TEMPLATE).save(out)
    return out
