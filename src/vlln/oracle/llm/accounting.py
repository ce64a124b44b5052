"""Token and cost accounting: what each request spent and the running total of a client."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Annotated

from pydantic import Field

from vlln.config import settings_dataclass
from vlln.oracle.llm.protocol import Usage

Price = Annotated[float, Field(ge=0.0, allow_inf_nan=False)]


@settings_dataclass
class Pricing:
    """Prices per 1000 tokens, in whatever currency the provider bills (OpenAI: USD).

    Zero (the default) for local servers, where tokens cost nothing but time.
    """

    prompt_per_1k: Price = 0.0
    completion_per_1k: Price = 0.0

    def cost(self, usage: Usage) -> float:
        return (
            usage.prompt_tokens * self.prompt_per_1k
            + usage.completion_tokens * self.completion_per_1k
        ) / 1000.0


@dataclass
class UsageLedger:
    """Running totals over every request a client made; safe to share between threads.

    ``requests`` counts requests answered by the server, ``cached_requests`` those answered
    from the cache (free), ``failed_requests`` those that gave no completion.
    """

    requests: int = 0
    cached_requests: int = 0
    failed_requests: int = 0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    cost: float = 0.0
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False, compare=False)

    @property
    def total_tokens(self) -> int:
        return self.prompt_tokens + self.completion_tokens

    def record(self, usage: Usage, cost: float) -> None:
        with self._lock:
            self.requests += 1
            self.prompt_tokens += usage.prompt_tokens
            self.completion_tokens += usage.completion_tokens
            self.cost += cost

    def record_cached(self) -> None:
        with self._lock:
            self.cached_requests += 1

    def record_failure(self) -> None:
        with self._lock:
            self.failed_requests += 1
