"""What a model agent needs from a vision-language model: one reply to one conversation.

Every model behind the model agent (an OpenAI-compatible server, a local transformers model)
implements :class:`VisionLanguageModel`. The conversation is the shared prompt
(:mod:`vlln.prompt`); ``images`` are the pictures its ``<image>`` tags stand for, in the same
order, each JPEG-encoded at the size its :class:`~vlln.prompt.ImageRef` calls for (level frames
384x384, the look-down frame 640x480), as the training data store them.

A backend never raises for a failed call: it returns a :class:`ModelReply` with ``text=None``
and the reason in ``error``, which the agent records as a server failure (a wasted step).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

from vlln.prompt import Conversation


@dataclass(frozen=True)
class ModelReply:
    """The model's raw output, or why there is none, and what the call cost."""

    text: str | None
    error: str | None = None
    latency_ms: float = 0.0
    prompt_tokens: int = 0
    completion_tokens: int = 0

    @property
    def failed(self) -> bool:
        return self.text is None


class VisionLanguageModel(Protocol):
    """A model that answers a conversation with images."""

    @property
    def backend(self) -> str:
        """A short name for records and run settings, e.g. ``openai:qwen2-vl@localhost``."""
        ...

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        """The reply to ``conversation``; ``images[i]`` is the JPEG for its i-th ``<image>``."""
        ...
