"""Model agents: a vision-language model behind the shared prompt and output grammar.

:class:`ModelAgent` is the loop (prompt, call, read, act); a backend implements
:class:`VisionLanguageModel` (``openai-vlm``: any OpenAI-compatible server).
"""

from vlln.agents.model.agent import MAX_FOLLOW_STEPS, ModelAgent
from vlln.agents.model.backend import ModelReply, VisionLanguageModel

__all__ = ["MAX_FOLLOW_STEPS", "ModelAgent", "ModelReply", "VisionLanguageModel"]
