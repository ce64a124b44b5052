"""Models with a released checkpoint's architecture and random weights, built offline.

Speed and memory on a GPU depend on the architecture, not on what the weights learnt, so
``vlln bench gpu-check`` measures training and decisions on Qwen2.5-VL-3B-Instruct's exact
shapes without downloading it: the configuration ships with the package
(``data/qwen2_5_vl_3b_instruct.json``, the public ``config.json`` and
``preprocessor_config.json`` values), and the tokenizer is :mod:`vlln.train.scratch`'s local one
(the embedding keeps the released vocabulary's size, so the output layer costs what it costs).
"""

from __future__ import annotations

import json
from importlib.resources import files
from pathlib import Path
from typing import Any

from vlln.agents.local.dependencies import require_model_extra
from vlln.errors import ConfigError
from vlln.train.scratch import local_tokenizer, write_random_model

ARCHITECTURES = {"qwen2.5-vl-3b-instruct": "qwen2_5_vl_3b_instruct.json"}
"""Released checkpoints whose architecture can be built, by name."""


def architecture(name: str) -> dict[str, Any]:
    """The shipped configuration of ``name``: text_config, vision_config, image_processor."""
    if name not in ARCHITECTURES:
        raise ConfigError(
            f"unknown architecture {name!r}; choose one of: {', '.join(ARCHITECTURES)}"
        )
    text = files("vlln.train").joinpath("data", ARCHITECTURES[name]).read_text(encoding="utf-8")
    loaded: dict[str, Any] = json.loads(text)
    return loaded


def build_released_architecture(
    out_dir: str | Path,
    name: str = "qwen2.5-vl-3b-instruct",
    seed: int = 0,
    device: str = "cpu",
    dtype: Any = None,
) -> Path:
    """Write a model of ``name``'s architecture with random weights drawn from ``seed``
    (made on ``device`` in ``dtype``), its processor and chat template, to ``out_dir``."""
    require_model_extra()
    from transformers import Qwen2VLImageProcessorPil

    spec = architecture(name)
    image_processor = Qwen2VLImageProcessorPil(**spec["image_processor"])
    return write_random_model(
        out_dir,
        local_tokenizer(),
        image_processor,
        spec["text_config"],
        spec["vision_config"],
        seed,
        device,
        dtype,
    )
