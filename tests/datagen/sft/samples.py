"""Reading an export back in tests."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any


def read_samples(out: Path) -> list[dict[str, Any]]:
    lines = (out / "sft.jsonl").read_text(encoding="utf-8").splitlines()
    return [json.loads(line) for line in lines]


def sample_key(sample: dict[str, Any]) -> tuple[int, int, str]:
    """(episode index, frame, kind) from an id such as
    ``house_00003/episode_000001/frame_000016/dialog/3``."""
    _, episode, frame, kind, _ = sample["id"].split("/")
    return int(episode.removeprefix("episode_")), int(frame.removeprefix("frame_")), kind


def episode_samples(samples: list[dict[str, Any]], episode: int) -> list[dict[str, Any]]:
    return [s for s in samples if sample_key(s)[0] == episode]
