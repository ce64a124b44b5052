"""The ``vlln`` agent from its options (``vlln eval --agent vlln --model PATH``): the
model-agent loop driving a local model fine-tuned by ``vlln train sft``."""

from __future__ import annotations

from pathlib import Path

from pydantic import Field

from vlln.agents.local.backend import MAX_NEW_TOKENS, load_backend
from vlln.agents.local.card import read_card
from vlln.agents.model.agent import ModelAgent
from vlln.agents.options import AgentOptions


class VllnOptions(AgentOptions):
    """Which local model the ``vlln`` agent runs, where, and how long its replies may be."""

    model: str = Field(min_length=1)
    """a model folder: the --out of vlln train sft, or a Qwen-VL checkpoint"""
    device: str | None = None
    """torch device of the model (none: cuda when there is one, else cpu)"""
    max_tokens: int = Field(MAX_NEW_TOKENS, ge=1)
    """longest reply in tokens"""

    @property
    def model_dir(self) -> str:
        """The model folder as an absolute path (what the backend loads)."""
        return str(Path(self.model).expanduser().resolve())


def vlln_agent(seed: int, options: VllnOptions) -> ModelAgent:
    """A model agent on the process's one copy of the local model named by ``--model``,
    prompting with the history length the model was trained with (its card)."""
    model = load_backend(options.model_dir, options.device, options.max_tokens)
    card = read_card(options.model_dir)
    return ModelAgent(model, seed, name="vlln", history_count=card.history_frames)
