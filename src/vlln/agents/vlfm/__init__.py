"""The VLFM-style baseline: frontiers ranked by a value map from a learned co-occurrence prior."""

from vlln.agents.vlfm.agent import ValueRanking, VlfmAgent

__all__ = ["ValueRanking", "VlfmAgent"]
