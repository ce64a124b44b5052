"""``scripts/gpu-check.sh`` in tiny mode on the CPU: every stage prints its figures as JSON
lines, and the side-by-side runs play the same decisions as one-at-a-time play; and the
shipped Qwen2.5-VL-3B-Instruct architecture has the released model's size."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import torch

from vlln.train.released import architecture

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_the_tiny_gpu_check_prints_every_figure(
    tmp_path: Path, one_house_dataset: Path, split_cache: Path
) -> None:
    # A kept --work folder: the check resumes the one-house build it makes (the session's,
    # built with the same settings) and reads the test split it plays from the cache there.
    shutil.copytree(one_house_dataset, tmp_path / "dataset")
    shutil.copytree(split_cache, tmp_path / "splits")
    env = os.environ | {"PYTHON": sys.executable, "VLLN_GPU_CHECK_TINY": "1"}
    flags = ["--decisions", "8", "--sft-steps", "2", "--max-tokens", "8", "--torch-threads", "1"]
    done = subprocess.run(
        ["bash", str(ROOT / "scripts" / "gpu-check.sh"), *flags, "--work", str(tmp_path)],
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    lines = [json.loads(line) for line in done.stdout.splitlines()]  # nothing but JSON
    notes = [line["note"] for line in lines if "note" in line]
    assert not [note for note in notes if "failed" in note], notes
    assert "model: tiny" in " ".join(notes)
    value = {line["metric"]: line["value"] for line in lines if "metric" in line}
    assert value["sft_steps"] == 2 and value["sft_steps_per_s"] > 0
    assert (tmp_path / "sft" / "model.safetensors").is_file()
    calls = value["decisions_concurrent1"]
    assert calls == value["decisions_concurrent4"] >= 8
    low, high = value["decisions_per_s_concurrent1"], value["decisions_per_s_concurrent4"]
    assert low > 0 and high > 0
    assert value["decisions_speedup_4_vs_1"] == pytest.approx(high / low, rel=0.01)
    assert value["side_by_side_records_match"] == 1.0
    assert value["render_fps"] > 0 and value["step_fps"] > 0


def test_the_shipped_3b_architecture_has_the_released_models_size() -> None:
    from transformers import Qwen2_5_VLConfig, Qwen2_5_VLForConditionalGeneration

    spec = architecture("qwen2.5-vl-3b-instruct")
    config = Qwen2_5_VLConfig(
        text_config=spec["text_config"],
        vision_config=spec["vision_config"],
        tie_word_embeddings=spec["text_config"]["tie_word_embeddings"],
    )
    with torch.device("meta"):
        model = Qwen2_5_VLForConditionalGeneration(config)
    total = sum(parameter.numel() for parameter in model.parameters())
    vision = sum(parameter.numel() for parameter in model.model.visual.parameters())
    # The model card's 3.75B parameters, 0.67B of them the vision tower.
    assert round(total / 1e9, 2) == 3.75
    assert round(vision / 1e9, 2) == 0.67
    assert model.lm_head.weight is model.model.language_model.embed_tokens.weight
