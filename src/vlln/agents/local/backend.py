"""A local transformers model that writes the next assistant turn of conversations.

Loaded once per process (:func:`load_backend` keeps it) and reused for every episode;
``generate`` takes several conversations at once, so episodes played side by side share one
forward pass. Decoding is greedy with at most 128 new tokens, as the reference evaluates.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from vlln.agents.local.dependencies import require_model_extra
from vlln.errors import ConfigError
from vlln.prompt import Turn

if TYPE_CHECKING:
    from PIL.Image import Image

MAX_NEW_TOKENS = 128


@dataclass(frozen=True)
class ChatRequest:
    """A conversation ending with a human turn, and its images in ``<image>`` order."""

    turns: tuple[Turn, ...]
    images: tuple[Image, ...]


@dataclass(frozen=True)
class Completion:
    text: str
    prompt_tokens: int
    completion_tokens: int
    latency_ms: float  # of the whole batch the request was in


class TransformersBackend:
    """A Qwen-VL-style model and its encoder on one device."""

    def __init__(
        self, model_dir: str | Path, device: str | None = None, max_new_tokens: int = MAX_NEW_TOKENS
    ) -> None:
        require_model_extra()
        import torch
        from transformers import AutoModelForImageTextToText

        from vlln.agents.local.encoding import ChatEncoder

        path = Path(model_dir)
        if not (path / "config.json").is_file():
            raise ConfigError(
                f"{model_dir} is not a model folder (no config.json); pass the --out folder of "
                "vlln train sft or a downloaded Qwen-VL checkpoint"
            )
        self.device = device or ("cuda" if torch.cuda.is_available() else "cpu")
        on_gpu = self.device.startswith("cuda")
        dtype = torch.bfloat16 if on_gpu and torch.cuda.is_bf16_supported() else torch.float32
        self.encoder = ChatEncoder.load(path)
        loader: Any = AutoModelForImageTextToText
        self.model = loader.from_pretrained(path, dtype=dtype)
        self.model.to(self.device).eval()
        self.max_new_tokens = max_new_tokens

    def generate(self, requests: Sequence[ChatRequest]) -> list[Completion]:
        """The model's next turn for every request, decoded greedily in one batch."""
        import torch

        if not requests:
            return []
        started = time.perf_counter()
        texts = [self.encoder.render(r.turns, add_generation_prompt=True) for r in requests]
        batch = self.encoder.encode(texts, [list(r.images) for r in requests], padding_side="left")
        inputs: dict[str, Any] = {key: value.to(self.device) for key, value in batch.items()}
        tokenizer = self.encoder.tokenizer
        with torch.inference_mode():
            output = self.model.generate(
                **inputs,
                do_sample=False,
                max_new_tokens=self.max_new_tokens,
                pad_token_id=tokenizer.pad_token_id,
                eos_token_id=self.encoder.end_of_turn_id,
            )
        prompt_length = inputs["input_ids"].shape[1]
        new_tokens = output[:, prompt_length:].cpu()
        latency = (time.perf_counter() - started) * 1000.0
        prompt_counts = inputs["attention_mask"].sum(dim=1).tolist()
        completions = []
        for row, tokens in enumerate(new_tokens):
            kept = tokens[tokens != tokenizer.pad_token_id]
            ended = (kept == self.encoder.end_of_turn_id).nonzero()
            if len(ended):
                kept = kept[: int(ended[0]) + 1]
            text = tokenizer.decode(kept, skip_special_tokens=True)
            completions.append(Completion(text, int(prompt_counts[row]), len(kept), latency))
        return completions


@lru_cache(maxsize=2)
def load_backend(model_dir: str, device: str | None = None) -> TransformersBackend:
    """The process's one backend per model folder and device (loaded on first use)."""
    return TransformersBackend(model_dir, device)
