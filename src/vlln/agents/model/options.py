"""The ``openai-vlm`` agent from its options (``vlln eval --base-url URL --model NAME``).

Options arrive as strings (they are stored in ``run.json``) and are checked here, each error
naming the option and how to fix it. The API key itself is never an option: only the name of
the environment variable that holds it. One client per distinct set of options serves every
episode of a process, so its connection pool, cache and usage ledger are shared. The server
must answer before any episode is played: an unreachable one would otherwise turn every step
into a failed call and the run into a complete one with SR 0.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from pathlib import Path

import httpx
import numpy as np

from vlln.agents.model.agent import ModelAgent
from vlln.agents.model.openai_vlm import DEFAULT_MAX_TOKENS, OpenAIVisionModel
from vlln.errors import ConfigError
from vlln.oracle.llm.openai_client import OpenAIChatClient, OpenAISettings

PROBE_TIMEOUT_S = 10.0  # the most the up-front check waits for the server's first answer
OPENAI_VLM_OPTIONS: dict[str, str] = {
    "base_url": "the server's OpenAI-compatible URL, e.g. http://localhost:8000/v1",
    "model": "the served model's name",
    "api_key_env": "environment variable holding the API key (default OPENAI_API_KEY)",
    "timeout_s": "deadline of each request, from connect to last byte (default 60 s)",
    "max_retries": "retries after a failed request (default 4)",
    "backoff_s": "first back-off in seconds, doubling per retry (default 0.5)",
    "max_tokens": f"longest reply in tokens (default {DEFAULT_MAX_TOKENS})",
    "temperature": "sampling temperature (default 0)",
    "cache_dir": "folder caching replies on disk (default: none)",
}


def openai_vlm_agent(seed: int, options: Mapping[str, str]) -> ModelAgent:
    """A model agent asking the server named by ``options`` (see :data:`OPENAI_VLM_OPTIONS`)."""
    unknown = sorted(set(options) - set(OPENAI_VLM_OPTIONS))
    if unknown:
        raise ConfigError(
            f"unknown openai-vlm option {unknown[0]!r}; known: {', '.join(OPENAI_VLM_OPTIONS)}"
        )
    for needed, flag in (("base_url", "--base-url URL"), ("model", "--model NAME")):
        if not options.get(needed):
            raise ConfigError(f"the openai-vlm agent needs {flag}")
    model = _shared_model(tuple(sorted(options.items())))
    return ModelAgent(model, seed, name="openai-vlm")


@lru_cache(maxsize=8)
def _shared_model(options: tuple[tuple[str, str], ...]) -> OpenAIVisionModel:
    values = dict(options)
    settings = OpenAISettings(
        model=values["model"],
        base_url=values["base_url"],
        api_key_env=values.get("api_key_env", "OPENAI_API_KEY"),
        timeout_s=_float(values, "timeout_s", 60.0),
        max_retries=_int(values, "max_retries", 4),
        backoff_base_s=_float(values, "backoff_s", 0.5),
        cache_dir=Path(values["cache_dir"]) if values.get("cache_dir") else None,
        retry_bad_replies=True,
    )
    check_server_answers(settings)
    client = OpenAIChatClient(settings, rng=np.random.default_rng(0))
    return OpenAIVisionModel(
        client,
        max_tokens=_int(values, "max_tokens", DEFAULT_MAX_TOKENS),
        temperature=_float(values, "temperature", 0.0),
    )


def check_server_answers(settings: OpenAISettings) -> None:
    """Raise :class:`ConfigError` unless something answers HTTP at ``settings.base_url``
    (any status will do: a server without ``GET /models`` still answers)."""
    url = settings.base_url.rstrip("/") + "/models"
    try:
        httpx.get(url, timeout=min(settings.timeout_s, PROBE_TIMEOUT_S))
    except httpx.HTTPError as error:
        raise ConfigError(
            f"the model server at {settings.base_url} does not answer "
            f"({type(error).__name__}: {str(error)[:120] or 'no reply'}); start it, or fix "
            "--base-url"
        ) from None


def _float(values: Mapping[str, str], name: str, default: float) -> float:
    return float(_number(values, name, default))


def _int(values: Mapping[str, str], name: str, default: int) -> int:
    number = _number(values, name, default)
    if number != int(number):
        raise ConfigError(f"openai-vlm option {name} must be a whole number, got {number}")
    return int(number)


def _number(values: Mapping[str, str], name: str, default: float) -> float:
    text = values.get(name)
    if text is None:
        return default
    try:
        return float(text)
    except ValueError:
        raise ConfigError(
            f"openai-vlm option {name} = {text!r} is not a number; {OPENAI_VLM_OPTIONS[name]}"
        ) from None
