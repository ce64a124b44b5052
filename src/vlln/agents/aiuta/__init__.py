"""The AIUTA-style baseline: a self-dialogue with a vision-language model decides when to ask."""

from vlln.agents.aiuta.agent import AiutaAgent, AiutaSettings

__all__ = ["AiutaAgent", "AiutaSettings"]
