"""The ``vlln`` agent from its options (``vlln eval --agent vlln --model PATH``): the
model-agent loop driving a local model fine-tuned by ``vlln train sft``."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from vlln.agents.local.backend import MAX_NEW_TOKENS, load_backend
from vlln.agents.model.agent import ModelAgent
from vlln.errors import ConfigError

VLLN_OPTIONS: dict[str, str] = {
    "model": "a model folder: the --out of vlln train sft, or a Qwen-VL checkpoint",
    "device": "torch device of the model (default cuda when there is one, else cpu)",
    "max_tokens": f"longest reply in tokens (default {MAX_NEW_TOKENS})",
}


@dataclass(frozen=True)
class LocalModelSettings:
    """Which model the options name, where it runs and how long its replies may be."""

    model_dir: str  # absolute
    device: str | None
    max_tokens: int = MAX_NEW_TOKENS


def vlln_agent(seed: int, options: Mapping[str, str]) -> ModelAgent:
    """A model agent on the process's one copy of the local model named by ``--model``."""
    settings = check_vlln_options(options)
    model = load_backend(settings.model_dir, settings.device, settings.max_tokens)
    return ModelAgent(model, seed, name="vlln")


def check_vlln_options(options: Mapping[str, str]) -> LocalModelSettings:
    """The settings the options name, checked without loading anything."""
    unknown = sorted(set(options) - set(VLLN_OPTIONS))
    if unknown:
        raise ConfigError(f"unknown vlln option {unknown[0]!r}; known: {', '.join(VLLN_OPTIONS)}")
    if not options.get("model"):
        raise ConfigError("the vlln agent needs --model PATH (a folder made by vlln train sft)")
    max_tokens = options.get("max_tokens", str(MAX_NEW_TOKENS))
    if not max_tokens.isdigit() or int(max_tokens) < 1:
        raise ConfigError(
            f"vlln option max_tokens = {max_tokens!r} must be a whole number of at least 1"
        )
    model_dir = str(Path(options["model"]).expanduser().resolve())
    return LocalModelSettings(model_dir, options.get("device"), int(max_tokens))
