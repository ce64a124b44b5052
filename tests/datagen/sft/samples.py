"""Reading an export back in tests."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

PIXEL_OUTPUT = re.compile(r"<move>(\d+) (\d+)")


def read_samples(out: Path) -> list[dict[str, Any]]:
    lines = (out / "sft.jsonl").read_text(encoding="utf-8").splitlines()
    return [json.loads(line) for line in lines]


def sample_frame(sample: dict[str, Any]) -> tuple[int, int]:
    """(episode index, frame) from an id such as ``house_00003/episode_000001/frame_000016``."""
    _, episode, frame = sample["id"].split("/")
    return int(episode.removeprefix("episode_")), int(frame.removeprefix("frame_"))


def episode_samples(samples: list[dict[str, Any]], episode: int) -> list[dict[str, Any]]:
    return [s for s in samples if sample_frame(s)[0] == episode]


def final_outputs(samples: list[dict[str, Any]]) -> list[str]:
    """The last model turn of each sample."""
    return [str(s["conversations"][-1]["value"]) for s in samples]
