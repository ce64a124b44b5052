"""The frontier-exploration baseline: own depth map, frontiers, ground-truth detector, dialog."""

from vlln.agents.frontier.agent import FrontierAgent, FrontierConfig

__all__ = ["FrontierAgent", "FrontierConfig"]
