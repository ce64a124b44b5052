"""Training data for the VLLN model: trajectories as multi-image, multi-turn conversations."""

from vlln.datagen.sft.config import SftConfig
from vlln.datagen.sft.export import SftSummary, export_sft

__all__ = ["SftConfig", "SftSummary", "export_sft"]
