"""Parameter groups: the vision tower learns at its own, lower rate."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from torch import nn


def is_vision_tower(name: str) -> bool:
    """Qwen-VL vision encoder parameters (``...visual.blocks``, ``...visual.patch_embed``);
    the merger that projects into the language model is trained at the main rate."""
    parts = name.split(".")
    return "visual" in parts and "merger" not in parts


def parameter_groups(
    model: nn.Module, learning_rate: float, vision_rate: float
) -> list[dict[str, Any]]:
    """Trainable parameters in two optimizer groups (empty groups left out), no weight decay."""
    vision: list[Any] = []
    rest: list[Any] = []
    for name, parameter in model.named_parameters():
        if parameter.requires_grad:
            (vision if is_vision_tower(name) else rest).append(parameter)
    groups = [
        {"params": rest, "lr": learning_rate, "weight_decay": 0.0},
        {"params": vision, "lr": vision_rate, "weight_decay": 0.0},
    ]
    return [group for group in groups if group["params"]]
