"""The settings of ``vlln train sft``; the defaults are the paper's (supplementary, "Training
Details"): full fine-tuning, LR 2e-5 with the vision tower at 5e-6, cosine schedule with 3 %
warm-up, no weight decay, gradient clipping at 1.0, 5 epochs, 2 samples per device."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from vlln.errors import ConfigError


@dataclass(frozen=True)
class TrainConfig:
    data_dir: Path  # a folder written by ``vlln data export-sft``
    model: str  # a local model folder or a Hugging Face model name
    out_dir: Path
    epochs: float = 5.0
    learning_rate: float = 2e-5
    vision_learning_rate: float = 5e-6
    warmup_ratio: float = 0.03
    batch_size: int = 2  # per device
    grad_accumulation: int = 1
    max_grad_norm: float = 1.0
    max_steps: int = -1  # > 0 stops after that many optimizer steps
    save_steps: int = 500
    save_limit: int = 2  # checkpoints kept
    logging_steps: int = 10
    workers: int = 4  # data-loader processes per device
    seed: int = 0
    lora: bool = False
    lora_rank: int = 16
    max_pixels: int | None = None  # caps the image processor's pixels per image
    gradient_checkpointing: bool | None = None  # None = when a GPU is used
    resume: Path | None = None  # None = the newest checkpoint in out_dir, if any

    def __post_init__(self) -> None:
        for name in ("learning_rate", "vision_learning_rate", "epochs", "max_grad_norm"):
            if not getattr(self, name) > 0:
                raise ConfigError(f"--{name.replace('_', '-')} must be > 0")
        if not 0 <= self.warmup_ratio < 1:
            raise ConfigError(f"warm-up ratio must be in [0, 1), got {self.warmup_ratio}")
        for name in ("batch_size", "grad_accumulation", "save_steps", "logging_steps"):
            if getattr(self, name) < 1:
                raise ConfigError(f"--{name.replace('_', '-')} must be >= 1")
        if self.workers < 0 or self.save_limit < 1 or self.lora_rank < 1:
            raise ConfigError("--workers must be >= 0, --save-limit and --lora-rank >= 1")
        if self.max_pixels is not None and self.max_pixels < 28 * 28:
            raise ConfigError(f"--max-pixels must be at least 784, got {self.max_pixels}")

    def settings(self) -> dict[str, Any]:
        return {
            key: str(value) if isinstance(value, Path) else value
            for key, value in asdict(self).items()
        }
