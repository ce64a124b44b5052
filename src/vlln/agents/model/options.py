"""The ``openai-vlm`` agent from its options (``vlln eval --base-url URL --model NAME``).

:class:`OpenAIVLMOptions` holds the options and their defaults. The API key itself is never an
option: only the name of the environment variable that holds it. One client per distinct set of
options serves every episode of a process, so its connection pool, cache and usage ledger are
shared, and so is its count of failed requests in a row, which stops the run at
``max_failures``. The server must answer before any episode is played: an unreachable one
would otherwise turn every step into a failed call and the run into a complete one with SR 0.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path
from typing import Annotated

import numpy as np
from pydantic import AfterValidator, AliasChoices, Field

from vlln.agents.model.agent import ModelAgent
from vlln.agents.model.openai_vlm import DEFAULT_MAX_TOKENS, OpenAIVisionModel
from vlln.agents.options import AgentOptions
from vlln.oracle.llm.openai_client import OpenAIChatClient, OpenAISettings, check_server_answers


def _absolute(path: str | None) -> str | None:
    return None if path is None else str(Path(path).expanduser().resolve())


def _flag(name: str, field: str) -> AliasChoices:
    """An option that ``vlln eval`` takes as ``--name`` (read by either name)."""
    return AliasChoices(field, name)


class OpenAIVLMOptions(AgentOptions):
    """Which OpenAI-compatible server and model the ``openai-vlm`` agent asks, and how."""

    base_url: str = Field(min_length=1)
    """the server's OpenAI-compatible URL, e.g. http://localhost:8000/v1"""
    model: str = Field(min_length=1)
    """the served model's name"""
    api_key_env: str = "OPENAI_API_KEY"
    """environment variable holding the API key"""
    timeout_s: float = Field(
        30.0, gt=0, validation_alias=AliasChoices("timeout_s", "model_timeout")
    )
    """deadline of each request, from connect to last byte, in seconds"""
    max_retries: int = Field(4, ge=0, validation_alias=_flag("model_retries", "max_retries"))
    """retries after a failed request"""
    max_failures: int = Field(4, ge=1, validation_alias=_flag("model_max_failures", "max_failures"))
    """failed requests in a row that stop the run (4 hanging ones: about 2 minutes)"""
    backoff_s: float = Field(0.5, ge=0)
    """first back-off in seconds, doubling per retry"""
    max_tokens: int = Field(DEFAULT_MAX_TOKENS, ge=1)
    """longest reply in tokens"""
    temperature: float = Field(0.0, ge=0)
    """sampling temperature"""
    cache_dir: Annotated[str | None, AfterValidator(_absolute)] = Field(
        None, validation_alias=_flag("model_cache", "cache_dir")
    )
    """folder caching replies on disk (none: no cache)"""


def openai_vlm_agent(seed: int, options: OpenAIVLMOptions) -> ModelAgent:
    """A model agent asking the server that ``options`` name."""
    return ModelAgent(_shared_model(options), seed, name="openai-vlm")


@lru_cache(maxsize=8)
def _shared_model(options: OpenAIVLMOptions) -> OpenAIVisionModel:
    client = shared_client(options)
    return OpenAIVisionModel(client, max_tokens=options.max_tokens, temperature=options.temperature)


@lru_cache(maxsize=8)
def shared_client(options: OpenAIVLMOptions) -> OpenAIChatClient:
    """One client per set of options (its connection pool, cache and ledger shared by every
    episode of the process), made once the server has answered."""
    settings = OpenAISettings(
        model=options.model,
        base_url=options.base_url,
        api_key_env=options.api_key_env,
        timeout_s=options.timeout_s,
        max_retries=options.max_retries,
        backoff_base_s=options.backoff_s,
        cache_dir=None if options.cache_dir is None else Path(options.cache_dir),
        retry_bad_replies=True,
        max_failures=options.max_failures,
    )
    check_server_answers(settings, "--base-url")
    return OpenAIChatClient(settings, rng=np.random.default_rng(0))
