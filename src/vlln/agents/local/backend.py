"""The ``vlln`` agent's model: a local transformers Qwen-VL-style model.

Implements :class:`vlln.agents.model.backend.VisionLanguageModel` for the model-agent loop.
Loaded once per process (:func:`load_backend`) and reused for every episode. Decoding is
greedy with at most 128 new tokens, as the reference evaluates. :meth:`generate_batch` answers
several conversations in one padded forward pass, for callers that play episodes side by side:
the model server of ``vlln eval --ray`` (:mod:`vlln.cluster.model_server`) and ``vlln bench
agent``; the local evaluation runner plays one episode at a time per process.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PIL import Image

from vlln.agents.local.dependencies import require_model_extra
from vlln.agents.model.backend import ModelReply
from vlln.errors import ConfigError
from vlln.files import open_image
from vlln.prompt import Conversation

if TYPE_CHECKING:
    import torch

MAX_NEW_TOKENS = 128


@dataclass(frozen=True)
class ChatRequest:
    """A conversation ending with a human turn, and its images in ``<image>`` order."""

    conversation: Conversation
    images: tuple[Image.Image, ...]


class TransformersBackend:
    """A Qwen-VL-style model and its encoder on one device."""

    def __init__(
        self, model_dir: str | Path, device: str | None = None, max_new_tokens: int = MAX_NEW_TOKENS
    ) -> None:
        require_model_extra()
        import torch
        from transformers import AutoModelForImageTextToText

        from vlln.agents.local.encoding import ChatEncoder, model_loading

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
        with model_loading(path):
            self.model = loader.from_pretrained(path, dtype=dtype)
        self.model.to(self.device).eval()
        self.max_new_tokens = max_new_tokens
        self._name = f"transformers:{path.name}@{self.device}"

    @property
    def backend(self) -> str:
        return self._name

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        """The reply to one conversation; ``images`` are its JPEGs in ``<image>`` order."""
        decoded = tuple(_decode(data) for data in images)
        try:
            return self.generate_batch([ChatRequest(conversation, decoded)])[0]
        except RuntimeError as error:  # out of device memory and the like: a failed call
            return ModelReply(text=None, error=f"{type(error).__name__}: {error}"[:300])

    def generate_many(
        self, calls: Sequence[tuple[Conversation, Sequence[bytes]]]
    ) -> list[ModelReply]:
        """The replies to several calls of :meth:`generate`, in one batch when it fits (greedy
        decoding with left padding gives each the reply it gets alone); when the batch fails
        (out of device memory), each call alone, so one bad call fails only itself."""
        requests = [
            ChatRequest(conversation, tuple(_decode(data) for data in images))
            for conversation, images in calls
        ]
        try:
            return self.generate_batch(requests)
        except RuntimeError:
            return [self.generate(conversation, images) for conversation, images in calls]

    def generate_batch(self, requests: Sequence[ChatRequest]) -> list[ModelReply]:
        """The model's next turn for every request, decoded greedily in one batch."""
        import torch

        if not requests:
            return []
        started = time.perf_counter()
        texts = [
            self.encoder.render(r.conversation.turns, add_generation_prompt=True) for r in requests
        ]
        batch = self.encoder.encode(texts, [list(r.images) for r in requests], padding_side="left")
        inputs: dict[str, torch.Tensor] = {
            key: value.to(self.device) for key, value in batch.items()
        }
        with torch.inference_mode():
            output = self.model.generate(
                **inputs,
                do_sample=False,
                max_new_tokens=self.max_new_tokens,
                pad_token_id=self.encoder.tokenizer.pad_token_id,
                eos_token_id=self.encoder.end_of_turn_id,
            )
        new_tokens = output[:, inputs["input_ids"].shape[1] :].cpu()
        latency = (time.perf_counter() - started) * 1000.0
        prompt_counts = inputs["attention_mask"].sum(dim=1).tolist()
        return [
            self._reply(tokens, int(prompt_counts[row]), latency)
            for row, tokens in enumerate(new_tokens)
        ]

    def _reply(self, tokens: torch.Tensor, prompt_tokens: int, latency_ms: float) -> ModelReply:
        """The text up to the first end of turn (the rest of a batch row is padding)."""
        ends = (tokens == self.encoder.end_of_turn_id).nonzero()
        kept = tokens[: int(ends[0]) + 1] if len(ends) else tokens
        text = self.encoder.tokenizer.decode(kept, skip_special_tokens=True)
        return ModelReply(
            text=text,
            latency_ms=latency_ms,
            prompt_tokens=prompt_tokens,
            completion_tokens=len(kept),
        )


def _decode(data: bytes) -> Image.Image:
    with open_image(data, "an image of the prompt") as image:
        return image.convert("RGB")


@lru_cache(maxsize=2)
def load_backend(
    model_dir: str, device: str | None = None, max_new_tokens: int = MAX_NEW_TOKENS
) -> TransformersBackend:
    """The process's one backend per model folder, device and reply length (loaded on first
    use)."""
    return TransformersBackend(model_dir, device, max_new_tokens)
