"""The language-model client protocol and the records that cross it.

The oracle needs one thing from a language model: the text of a chat completion. Keeping the
interface that small lets the offline model, a hosted GPT-4o and a local vLLM or Ollama server
stand in for one another, and lets tests use a scripted server.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, Protocol

from vlln.errors import VllnError

Role = Literal["system", "user", "assistant"]


@dataclass(frozen=True)
class TextPart:
    """A piece of text in a message that also holds images."""

    text: str


@dataclass(frozen=True)
class ImagePart:
    """A picture in a message: an ``https://`` URL or a ``data:image/jpeg;base64,...`` URL."""

    url: str


ContentPart = TextPart | ImagePart


@dataclass(frozen=True)
class Message:
    """One chat message in the OpenAI chat format: plain text, or text and images in order."""

    role: Role
    content: str | tuple[ContentPart, ...]

    @property
    def text(self) -> str:
        """The message's text, its images left out."""
        if isinstance(self.content, str):
            return self.content
        return "".join(part.text for part in self.content if isinstance(part, TextPart))

    def to_json(self) -> dict[str, Any]:
        if isinstance(self.content, str):
            return {"role": self.role, "content": self.content}
        parts = [
            {"type": "text", "text": part.text}
            if isinstance(part, TextPart)
            else {"type": "image_url", "image_url": {"url": part.url}}
            for part in self.content
        ]
        return {"role": self.role, "content": parts}


@dataclass(frozen=True)
class Usage:
    """Tokens one request spent, as the server counted them (zero when it does not say)."""

    prompt_tokens: int = 0
    completion_tokens: int = 0

    @property
    def total_tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens


@dataclass(frozen=True)
class Completion:
    """A model's reply. ``cached`` replies cost nothing: their usage and latency are zero."""

    text: str
    usage: Usage
    backend: str  # e.g. "offline" or "openai:gpt-4o@api.openai.com"
    cached: bool = False
    latency_ms: float = 0.0  # wall time of the request, retries and back-off included


class LanguageModel(Protocol):
    """Anything that completes a chat: the offline model or an HTTP client."""

    @property
    def backend(self) -> str:
        """A short name for records: which model, served by whom."""
        ...

    def complete(
        self, messages: list[Message], *, max_tokens: int, temperature: float
    ) -> Completion: ...


class LanguageModelError(VllnError, RuntimeError):
    """A language model gave no usable completion; callers fall back to offline logic."""

    latency_ms: float = 0.0  # time spent before giving up, retries included


class LanguageModelUnavailableError(LanguageModelError):
    """The server could not be reached or kept failing (timeouts, 429, 5xx) after retries."""


class LanguageModelRequestError(LanguageModelError):
    """The server refused the request (a 4xx other than 429); retrying would not help."""

    def __init__(self, message: str, status: int) -> None:
        super().__init__(message)
        self.status = status


class LanguageModelReplyError(LanguageModelError):
    """The server answered, but not with a chat completion (bad JSON, no choices, no text)."""
