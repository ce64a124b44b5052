"""The ``vlln`` agent from its options (``vlln eval --agent vlln --model PATH``): the
model-agent loop driving a local model fine-tuned by ``vlln train sft``."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from vlln.agents.model.agent import ModelAgent
from vlln.errors import ConfigError

VLLN_OPTIONS: dict[str, str] = {
    "model": "a model folder: the --out of vlln train sft, or a Qwen-VL checkpoint",
    "device": "torch device of the model (default cuda when there is one, else cpu)",
}


def vlln_agent(seed: int, options: Mapping[str, str]) -> ModelAgent:
    """A model agent on the process's one copy of the local model named by ``--model``."""
    from vlln.agents.local.backend import load_backend

    unknown = sorted(set(options) - set(VLLN_OPTIONS))
    if unknown:
        raise ConfigError(f"unknown vlln option {unknown[0]!r}; known: {', '.join(VLLN_OPTIONS)}")
    if not options.get("model"):
        raise ConfigError("the vlln agent needs --model PATH (a folder made by vlln train sft)")
    model_dir = str(Path(options["model"]).expanduser().resolve())
    return ModelAgent(load_backend(model_dir, options.get("device")), seed, name="vlln")
