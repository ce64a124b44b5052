"""The settings of ``vlln train sft``; the defaults are the paper's (supplementary, "Training
Details"): full fine-tuning, LR 2e-5 with the vision tower at 5e-6, cosine schedule with 3 %
warm-up, no weight decay, gradient clipping at 1.0, 5 epochs, 2 samples per device."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import AliasChoices, Field

from vlln.config import Config


def _flag(name: str, field: str) -> AliasChoices:
    """A flag named ``--name`` for ``field`` (both read from stored settings)."""
    return AliasChoices(name, field)


class TrainConfig(Config):
    """Supervised fine-tuning of a vision-language model on a training export."""

    data_dir: Annotated[Path, Field(validation_alias=_flag("data", "data_dir"))]
    """a folder made by vlln data export-sft"""
    model: str
    """model folder or Hugging Face name"""
    out_dir: Annotated[Path, Field(validation_alias=_flag("out", "out_dir"))]
    """output folder (a rerun resumes it)"""
    epochs: float = Field(5.0, gt=0)
    """epochs"""
    learning_rate: float = Field(2e-5, gt=0, validation_alias=_flag("lr", "learning_rate"))
    """learning rate"""
    vision_learning_rate: float = Field(
        5e-6, gt=0, validation_alias=_flag("vision_lr", "vision_learning_rate")
    )
    """the vision tower's learning rate"""
    warmup_ratio: float = Field(0.03, ge=0, lt=1)
    """share of steps that warm the learning rate up"""
    batch_size: int = Field(2, ge=1)
    """samples per device"""
    grad_accumulation: int = Field(
        1, ge=1, validation_alias=_flag("grad_accum", "grad_accumulation")
    )
    """gradient accumulation steps"""
    max_grad_norm: float = Field(1.0, gt=0)
    """gradient clipping norm"""
    max_steps: int = -1
    """stop after N optimizer steps (-1: run the epochs)"""
    save_steps: int = Field(500, ge=1)
    """checkpoint every N steps"""
    save_limit: int = Field(2, ge=1)
    """checkpoints kept"""
    logging_steps: int = Field(10, ge=1)
    """log the loss every N steps"""
    workers: int = Field(4, ge=0)
    """data-loader processes per device"""
    seed: int = 0
    """seed of the data order and new weights"""
    lora: bool = False
    """train LoRA adapters (small GPUs)"""
    lora_rank: int = Field(16, ge=1)
    """LoRA rank"""
    max_pixels: int | None = Field(None, ge=28 * 28)
    """cap on pixels per image, fewer tokens (none: the processor's)"""
    gradient_checkpointing: bool | None = None
    """recompute activations (none: on with a GPU)"""
    resume: Path | None = None
    """a checkpoint folder (none: the newest in --out)"""


class NewModelConfig(Config):
    """``vlln train new-model``: a randomly initialised Qwen2.5-VL-style model, built offline."""

    out: Path
    """model folder (replaced on a rerun)"""
    size: Literal["tiny", "small", "base"] = "tiny"
    """tiny (tests), small (the CPU recipe) or base (a GPU); docs/learning.md"""
    seed: int = 0
    """seed of its weights"""
