"""The frontier-exploration baseline: own depth map, frontiers, ground-truth detector, dialog."""

from vlln.agents.frontier.agent import FrontierAgent
from vlln.agents.frontier.config import FrontierConfig

__all__ = ["FrontierAgent", "FrontierConfig"]
