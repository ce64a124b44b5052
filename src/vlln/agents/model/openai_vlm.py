"""The ``openai-vlm`` backend: any server speaking OpenAI's chat format with images.

vLLM, SGLang, Ollama and hosted APIs all take ``image_url`` content parts; the pictures travel
inline as ``data:image/jpeg;base64,...`` URLs, each where its ``<image>`` tag stands in the
prompt (the tag itself is left out, as chat templates put their own image tokens there).
Human turns become ``user`` messages and the model's own turns ``assistant`` messages.

Requests go through the oracle's client (:class:`OpenAIChatClient`): HTTPS or loopback only,
key from an environment variable, timeouts, retries with back-off (garbage replies included),
an optional disk cache, token and cost accounting. A call that still fails is returned as a
:class:`ModelReply` without text, which the agent records as a server failure.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence

from vlln.agents.model.backend import ModelReply
from vlln.errors import ConfigError
from vlln.oracle.llm.openai_client import OpenAIChatClient
from vlln.oracle.llm.protocol import (
    ContentPart,
    ImagePart,
    LanguageModelError,
    Message,
    TextPart,
)
from vlln.prompt import IMAGE_TAG, Conversation

DEFAULT_MAX_TOKENS = 128  # room for the longest valid output, a 300-character question


def chat_messages(conversation: Conversation, images: Sequence[bytes]) -> list[Message]:
    """The conversation as chat messages, each ``<image>`` replaced by its JPEG's data URL."""
    if len(images) != len(conversation.images):
        raise ConfigError(
            f"the conversation shows {len(conversation.images)} images but {len(images)} were given"
        )
    pictures = iter(images)
    messages = []
    for turn in conversation.turns:
        if turn.role == "gpt":  # the model's own turns are plain text
            messages.append(Message("assistant", turn.text))
            continue
        parts: list[ContentPart] = []
        for index, text in enumerate(turn.text.split(IMAGE_TAG)):
            if index:
                parts.append(ImagePart(jpeg_data_url(next(pictures))))
            if text:
                parts.append(TextPart(text))
        messages.append(Message("user", tuple(parts)))
    return messages


def jpeg_data_url(jpeg: bytes) -> str:
    return "data:image/jpeg;base64," + base64.b64encode(jpeg).decode("ascii")


class OpenAIVisionModel:
    """A :class:`~vlln.agents.model.backend.VisionLanguageModel` over an OpenAI-style server."""

    def __init__(
        self,
        client: OpenAIChatClient,
        *,
        max_tokens: int = DEFAULT_MAX_TOKENS,
        temperature: float = 0.0,
    ) -> None:
        self.client = client
        self.max_tokens = max_tokens
        self.temperature = temperature

    @property
    def backend(self) -> str:
        return self.client.backend

    def generate(self, conversation: Conversation, images: Sequence[bytes]) -> ModelReply:
        messages = chat_messages(conversation, images)
        try:
            completion = self.client.complete(
                messages, max_tokens=self.max_tokens, temperature=self.temperature
            )
        except LanguageModelError as error:
            return ModelReply(None, str(error)[:500], error.latency_ms)
        usage = completion.usage
        return ModelReply(
            completion.text,
            None,
            completion.latency_ms,
            usage.prompt_tokens,
            usage.completion_tokens,
        )

    def close(self) -> None:
        self.client.close()
