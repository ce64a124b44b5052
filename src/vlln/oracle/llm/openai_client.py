"""A client for any server speaking OpenAI's chat-completions format: GPT-4o, vLLM, Ollama.

``POST {base_url}/chat/completions`` with the model, the messages, ``max_tokens`` and
``temperature``; nothing vendor-specific beyond that format. The API key comes from an
environment variable (its name is a setting) and travels only as a Bearer header over HTTPS;
plain HTTP is accepted for loopback hosts alone (a local vLLM or Ollama), so a key never
crosses a network in clear. The key is never logged and is masked in error messages.

``timeout_s`` is a deadline for each request as a whole (:mod:`.deadline`), so a server that
trickles its reply is cut off like one that says nothing; a reply body is read up to
:data:`MAX_REPLY_BYTES`, so a server that ignores ``max_tokens`` cannot fill the memory.
Timeouts, connection errors, 429 and 5xx answers are retried with exponential back-off and
jitter drawn from the caller's generator; a 429's ``Retry-After`` is waited out (up to the
back-off cap, so a server cannot stall a run). Other 4xx answers are not retried. Replies
that are not chat completions raise :class:`LanguageModelReplyError`, or are retried like a
5xx with ``retry_bad_replies``. Messages may hold images (data URLs). Completions are cached
on disk when a cache folder is set, and every request is added to a :class:`UsageLedger`.

With ``max_failures`` set, that many failed requests in a row (any success resets the count)
raise :class:`~vlln.errors.ServerDownError` instead of a language-model error, which callers
do not fall back from: a run stops in minutes instead of waiting out every retry of every
step against a server that is down. Unset, a caller may fall back for ever (a web study's
oracle, which answers from rules meanwhile).
"""

from __future__ import annotations

import email.utils
import json
import logging
import math
import os
import time
from dataclasses import field
from pathlib import Path
from typing import Annotated, Any, Self

import httpcore
import httpx
import numpy as np
from pydantic import AfterValidator, Field, field_validator, model_validator

from vlln.config import settings_dataclass
from vlln.errors import ConfigError, DataFormatError, ServerDownError
from vlln.files import parse_json
from vlln.http.addresses import is_loopback
from vlln.oracle.llm.accounting import Pricing, UsageLedger
from vlln.oracle.llm.cache import ResponseCache, cache_key
from vlln.oracle.llm.deadline import DeadlineBackend, deadline
from vlln.oracle.llm.protocol import (
    Completion,
    LanguageModelError,
    LanguageModelReplyError,
    LanguageModelRequestError,
    LanguageModelUnavailableError,
    Message,
    Usage,
)

logger = logging.getLogger(__name__)

_ERROR_EXCERPT = 300  # characters of a server's error body quoted in an exception
MAX_REPLY_BYTES = 1 << 20  # a completion of a few hundred tokens is a few kilobytes
_TRANSPORT_ERRORS = (httpcore.TimeoutException, httpcore.NetworkError, httpcore.RemoteProtocolError)
PROBE_TIMEOUT_S = 10.0  # the most the up-front check waits for the server's first answer


def check_base_url(base_url: str) -> str:
    """``base_url`` if it is HTTPS, or HTTP to a loopback host; else :class:`ConfigError`."""
    try:
        url = httpx.URL(base_url)
    except (httpx.InvalidURL, TypeError) as error:
        raise ConfigError(f"{base_url!r} is not a URL: {error}") from None
    if url.scheme == "https" and url.host:
        return base_url
    if url.scheme == "http" and is_loopback(url.host):
        return base_url
    raise ConfigError(
        f"{base_url!r} must use https:// (plain http:// is only allowed for "
        "localhost, 127.0.0.0/8 and ::1, where the key never leaves the machine)"
    )


Seconds = Annotated[float, Field(ge=0.0, allow_inf_nan=False)]


@settings_dataclass
class OpenAISettings:
    """Where the model is served and how patiently to talk to it."""

    model: str
    base_url: Annotated[str, AfterValidator(check_base_url)] = "https://api.openai.com/v1"
    api_key_env: str = "OPENAI_API_KEY"  # unset or empty: no Authorization header
    # deadline of each request (attempt), from connect to last byte
    timeout_s: float = Field(default=30.0, gt=0.0, allow_inf_nan=False)
    max_retries: int = Field(default=4, ge=0, strict=True)  # retries after the first attempt
    backoff_base_s: Seconds = 0.5  # first back-off; doubles on each retry
    backoff_max_s: Seconds = 30.0  # cap of one wait, Retry-After included
    pricing: Pricing = field(default_factory=Pricing)
    cache_dir: Path | None = None  # None: no disk cache
    # Retry replies that are not chat completions (a body that is not JSON, no choices), as a
    # proxy or an overloaded server sometimes sends; off for the oracle, which falls back.
    retry_bad_replies: bool = False
    # failed requests in a row that raise ServerDownError (None: never, callers fall back)
    max_failures: int | None = Field(default=None, ge=1, strict=True)

    @field_validator("model")
    @classmethod
    def _names_a_model(cls, model: str) -> str:
        if not model.strip():
            raise ConfigError("must name the served model, e.g. 'gpt-4o'")
        return model

    @field_validator("api_key_env")
    @classmethod
    def _names_a_variable(cls, name: str) -> str:
        if not name.isidentifier():
            raise ConfigError(f"must be an environment variable name, got {name!r}")
        return name

    @model_validator(mode="after")
    def _backoff_base_below_max(self) -> Self:
        if not self.backoff_base_s <= self.backoff_max_s:
            raise ConfigError(
                f"back-off needs backoff_base_s <= backoff_max_s, got {self.backoff_base_s!r} "
                f"and {self.backoff_max_s!r}"
            )
        return self


class OpenAIChatClient:
    """Chat completions over HTTP; one connection pool, reused across requests.

    ``rng`` draws the back-off jitter, so retry timing is reproducible given the seed.
    """

    def __init__(
        self,
        settings: OpenAISettings,
        *,
        rng: np.random.Generator,
        ledger: UsageLedger | None = None,
    ) -> None:
        self.settings = settings
        self.rng = rng
        self.ledger = ledger if ledger is not None else UsageLedger()
        self.cache = ResponseCache(settings.cache_dir) if settings.cache_dir is not None else None
        self.backend = f"openai:{settings.model}@{httpx.URL(settings.base_url).host}"
        self._url = settings.base_url.rstrip("/") + "/chat/completions"
        self._api_key = os.environ.get(settings.api_key_env, "")
        headers = {"Content-Type": "application/json"}
        if self._api_key:
            headers["Authorization"] = f"Bearer {self._api_key}"
        self._headers = list(headers.items())
        self._failures_in_row = 0
        self._http = httpcore.ConnectionPool(
            ssl_context=httpx.create_ssl_context(), network_backend=DeadlineBackend()
        )

    def __repr__(self) -> str:
        key = "set" if self._api_key else "not set"
        return f"OpenAIChatClient({self.backend!r}, key from ${self.settings.api_key_env}: {key})"

    def close(self) -> None:
        self._http.close()

    def __enter__(self) -> OpenAIChatClient:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def complete(
        self, messages: list[Message], *, max_tokens: int, temperature: float
    ) -> Completion:
        """The model's reply to ``messages``, from the cache when it was asked before."""
        if isinstance(max_tokens, bool) or max_tokens < 1:
            raise ConfigError(f"max_tokens must be a whole number >= 1, got {max_tokens!r}")
        if not (0.0 <= temperature <= 2.0):
            raise ConfigError(f"temperature must be in [0, 2], got {temperature!r}")
        params = {"max_tokens": max_tokens, "temperature": temperature}
        key = cache_key(self.settings.base_url, self.settings.model, messages, params)
        if self.cache is not None:
            text = self.cache.get(key)
            if text is not None:
                self.ledger.record_cached()
                return Completion(text, Usage(), self.backend, cached=True)
        body = {"model": self.settings.model, "messages": [m.to_json() for m in messages]}
        start = time.perf_counter()
        try:
            text, usage = self._request({**body, **params})
        except LanguageModelError as error:
            self.ledger.record_failure()
            error.latency_ms = (time.perf_counter() - start) * 1000.0
            raise
        latency_ms = (time.perf_counter() - start) * 1000.0
        self.ledger.record(usage, self.settings.pricing.cost(usage))
        if self.cache is not None:
            self.cache.put(key, text)
        return Completion(text, usage, self.backend, cached=False, latency_ms=latency_ms)

    def _request(self, body: dict[str, Any]) -> tuple[str, Usage]:
        """One request with its retries, each failed attempt counted toward ``max_failures``."""
        attempts = self.settings.max_retries + 1
        problem = ""
        retry_after: float | None = None
        for attempt in range(attempts):
            if attempt:
                self._wait(attempt - 1, retry_after, problem)
            try:
                reply = self._attempt(body)
            except _Retryable as retry:
                problem, retry_after = retry.problem, retry.retry_after
                self._count_failure(problem)
                continue
            except LanguageModelError as error:
                self._count_failure(str(error))
                raise
            self._failures_in_row = 0
            return reply
        raise LanguageModelUnavailableError(
            f"{self.backend} gave no completion in {attempts} attempts (last: {problem}); check "
            "that the server is up and base_url is right, or raise timeout_s or max_retries"
        )

    def _attempt(self, body: dict[str, Any]) -> tuple[str, Usage]:
        """One attempt's completion; :class:`_Retryable` for what a retry may cure."""
        try:
            response = self._post(body)
        except httpcore.TimeoutException as error:
            raise _Retryable(
                f"no complete reply within the {self.settings.timeout_s:g} s deadline "
                f"({type(error).__name__}: {self._masked(str(error))})"
            ) from None
        except _TRANSPORT_ERRORS as error:  # connection errors
            raise _Retryable(f"{type(error).__name__}: {self._masked(str(error))}") from None
        except LanguageModelReplyError as error:  # a reply too long to read
            raise self._bad_reply(error) from None
        status = response.status_code
        if status == 429 or status >= 500:
            retry_after = _retry_after_s(response) if status == 429 else None
            raise _Retryable(f"HTTP {status}: {self._excerpt(response)}", retry_after)
        if status >= 400:
            key_env = self.settings.api_key_env
            hint = f"; check the key in ${key_env}" if status in (401, 403) else ""
            raise LanguageModelRequestError(
                f"{self.backend} refused the request with HTTP {status}{hint}: "
                f"{self._excerpt(response)}",
                status,
            )
        try:
            return _parse_completion(response, self.backend)
        except LanguageModelReplyError as error:
            raise self._bad_reply(error) from None

    def _bad_reply(self, error: LanguageModelReplyError) -> Exception:
        """A reply that is no completion: retried with ``retry_bad_replies``, else raised."""
        return _Retryable(str(error)) if self.settings.retry_bad_replies else error

    def _count_failure(self, problem: str) -> None:
        """One more failed request in a row; at ``max_failures`` the server is given up on."""
        self._failures_in_row += 1
        limit = self.settings.max_failures
        if limit is not None and self._failures_in_row >= limit:
            raise ServerDownError(
                f"{self.backend} failed {self._failures_in_row} requests in a row (last: "
                f"{' '.join(problem.split())[:300]}); the run stops, its finished episodes "
                "kept: fix the server and rerun the same command"
            )

    def _post(self, body: dict[str, Any]) -> httpx.Response:
        """One attempt: POST ``body``, the whole exchange bounded by the deadline
        ``timeout_s`` and the reply body by :data:`MAX_REPLY_BYTES`."""
        content = json.dumps(body, ensure_ascii=False, allow_nan=False).encode("utf-8")
        seconds = self.settings.timeout_s
        limits = {"connect": seconds, "read": seconds, "write": seconds, "pool": seconds}
        with (
            deadline(seconds),
            self._http.stream(
                "POST",
                self._url,
                headers=self._headers,
                content=content,
                extensions={"timeout": limits},
            ) as response,
        ):
            data = bytearray()
            for chunk in response.iter_stream():
                data += chunk
                if len(data) > MAX_REPLY_BYTES:
                    raise LanguageModelReplyError(
                        f"{self.backend} answered more than {MAX_REPLY_BYTES} bytes; a "
                        "completion of max_tokens tokens is far shorter (does the server "
                        "ignore max_tokens?)"
                    )
        return httpx.Response(response.status, headers=response.headers, content=bytes(data))

    def _wait(self, attempt: int, retry_after: float | None, problem: str) -> None:
        settings = self.settings
        cap = min(settings.backoff_max_s, settings.backoff_base_s * 2.0**attempt)
        delay = cap * (0.5 + 0.5 * float(self.rng.random()))  # "equal jitter"
        if retry_after is not None:
            delay = max(delay, min(retry_after, settings.backoff_max_s))
        logger.info(
            "%s: %s; retry %d of %d in %.3f s",
            self.backend,
            problem,
            attempt + 1,
            settings.max_retries,
            delay,
        )
        time.sleep(delay)

    def _masked(self, text: str) -> str:
        return text.replace(self._api_key, "***") if self._api_key else text

    def _excerpt(self, response: httpx.Response) -> str:
        return self._masked(response.text[:_ERROR_EXCERPT]) or "(empty body)"


class _Retryable(Exception):
    """An attempt that failed in a way a later attempt may not: why, and the server's wait."""

    def __init__(self, problem: str, retry_after: float | None = None) -> None:
        super().__init__(problem)
        self.problem = problem
        self.retry_after = retry_after


def check_server_answers(settings: OpenAISettings, flag: str) -> None:
    """Raise :class:`ConfigError` unless something answers HTTP at ``settings.base_url``
    (any status will do: a server without ``GET /models`` still answers), so a run does not
    play every episode against a server that is not there; ``flag`` sets the URL."""
    url = settings.base_url.rstrip("/") + "/models"
    try:
        httpx.get(url, timeout=min(settings.timeout_s, PROBE_TIMEOUT_S))
    except httpx.HTTPError as error:
        raise ConfigError(
            f"the model server at {settings.base_url} does not answer "
            f"({type(error).__name__}: {str(error)[:120] or 'no reply'}); start it, or fix "
            f"{flag}"
        ) from None


def _retry_after_s(response: httpx.Response) -> float | None:
    """Seconds from a ``Retry-After`` header (delta-seconds or an HTTP date), if any."""
    value = response.headers.get("Retry-After")
    if value is None:
        return None
    try:
        seconds = float(value)
    except ValueError:
        try:
            when = email.utils.parsedate_to_datetime(value)
        except (TypeError, ValueError):
            return None
        seconds = when.timestamp() - time.time()
    return max(0.0, seconds) if math.isfinite(seconds) else None


def _parse_completion(response: httpx.Response, backend: str) -> tuple[str, Usage]:
    """The first choice's text and the usage, or :class:`LanguageModelReplyError`."""
    try:
        data = parse_json(response.content)
    except DataFormatError as error:
        raise LanguageModelReplyError(
            f"{backend} answered HTTP {response.status_code} with a body that is not plain "
            f"JSON ({str(error)[:_ERROR_EXCERPT]}): {response.text[:_ERROR_EXCERPT]!r}"
        ) from None
    if not isinstance(data, dict):
        raise LanguageModelReplyError(f"{backend} answered JSON that is not an object")
    choices = data.get("choices")
    if not isinstance(choices, list) or not choices:
        raise LanguageModelReplyError(
            f"{backend} answered without 'choices'; is base_url a chat-completions server?"
        )
    first = choices[0]
    message = first.get("message") if isinstance(first, dict) else None
    text = message.get("content") if isinstance(message, dict) else None
    if not isinstance(text, str) or not text.strip():
        raise LanguageModelReplyError(
            f"{backend} answered a choice without text in message.content: {str(first)[:200]}"
        )
    return text, _parse_usage(data.get("usage"), backend)


def _parse_usage(usage: object, backend: str) -> Usage:
    if usage is None:
        return Usage()
    if not isinstance(usage, dict):
        raise LanguageModelReplyError(f"{backend} answered a 'usage' that is not an object")
    counts = []
    for name in ("prompt_tokens", "completion_tokens"):
        value = usage.get(name, 0)
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            raise LanguageModelReplyError(
                f"{backend} answered usage.{name} = {value!r}; expected a whole number >= 0"
            )
        counts.append(value)
    return Usage(counts[0], counts[1])
