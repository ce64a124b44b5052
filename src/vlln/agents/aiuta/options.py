"""The ``aiuta`` agent from its options: the OpenAI-compatible server as for ``openai-vlm``,
and the self-dialogue's knobs (``vlln eval --agent aiuta --base-url URL --model NAME``)."""

from __future__ import annotations

from pydantic import Field

from vlln.agents.aiuta.agent import AiutaAgent, AiutaSettings
from vlln.agents.model.options import OpenAIVLMOptions, shared_client

_DEFAULTS = AiutaSettings()


class AiutaOptions(OpenAIVLMOptions):
    """Which server and model answer the self-dialogue, and its thresholds."""

    max_tokens: int = Field(_DEFAULTS.max_tokens, ge=1)
    """longest reply in tokens (descriptions need more than an action)"""
    self_questions: int = Field(_DEFAULTS.self_questions, ge=0)
    """questions the Self-Questioner asks itself about each object"""
    stop_score: float = Field(_DEFAULTS.stop_score, ge=0, le=10)
    """alignment score (0-10) at or above which the agent stops at the object"""
    skip_score: float = Field(_DEFAULTS.skip_score, ge=0, le=10)
    """alignment score below which the agent explores on without asking"""


def aiuta_agent(seed: int, options: AiutaOptions, detector: str = "truth") -> AiutaAgent:
    """An AIUTA-style agent asking the server that ``options`` name."""
    settings = AiutaSettings(
        self_questions=options.self_questions,
        stop_score=options.stop_score,
        skip_score=options.skip_score,
        max_tokens=options.max_tokens,
        temperature=options.temperature,
    )
    return AiutaAgent(shared_client(options), seed, detector, settings)
