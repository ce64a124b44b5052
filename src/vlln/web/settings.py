"""The settings of ``vlln serve web``: the app's limits (:class:`WebLimits`), which episodes
it serves and where it listens. Imported when the command is used."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Self

from pydantic import Field, model_validator

from vlln.web.config import DEFAULT_HOST, DEFAULT_PORT, DEFAULT_TOKEN_ENV, WebLimits
from vlln.world.options import PresetOptions


class ServeWebCommand(WebLimits, PresetOptions):
    """``vlln serve web``: a study's settings, its episodes (on the benchmark's houses unless
    --preset says otherwise) and its address."""

    split: str | None = None
    """built-in split (none: test, unless --episode-file)"""
    episode_file: Path | None = None
    """released-format episode file (.json.gz)"""
    houses: Annotated[int | None, Field(ge=1)] = None
    """houses of the split (none: all of it)"""
    episodes: Annotated[int | None, Field(ge=1)] = None
    """serve N episodes spread over the houses (none: every episode)"""
    budget: Annotated[int | None, Field(ge=0)] = None
    """answered questions (none: 5 on IIGN, 0 on the other tasks)"""
    out: Path
    """output folder (episode records; resumed)"""
    host: str = DEFAULT_HOST
    """address to listen on (loopback only unless a token is set)"""
    port: Annotated[int, Field(ge=0, le=65535)] = DEFAULT_PORT
    """port"""
    token_env: str = DEFAULT_TOKEN_ENV
    """environment variable with the access token; required off loopback"""
    llm_model: str | None = None
    """offer the language-model oracle with this model"""
    llm_base_url: str | None = None
    """its OpenAI-compatible URL (none: OpenAI's)"""
    agent_option: tuple[str, ...] = ()
    """offer an agent that takes options, e.g. openai-vlm.base_url=URL and
    openai-vlm.model=NAME (AGENT.KEY=VALUE, repeatable; a comma separates values)"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""

    @model_validator(mode="after")
    def _one_source(self) -> Self:
        if self.split is not None and self.episode_file is not None:
            raise ValueError(
                "--split and --episode-file do not mix: serve a built-in split or a file"
            )
        return self
