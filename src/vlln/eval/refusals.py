"""Refused episodes of a run: ``DIR/episodes.refused.jsonl``, one line per (episode, budget).

An episode the environment refuses (:mod:`vlln.tasks.refusal`: its start or goals cannot be
reached on their own storeys) has no episode line; its refusal is kept here with the reason,
so that the run's health counts it, a resume does not play it again, and ``vlln score`` and
``vlln report`` name it. A line that cannot be read is not counted (the episode is then
played again on a resume).
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from pathlib import Path

from vlln.eval.run_dir import REFUSED_FILE
from vlln.files import ReadCap, parse_json, writing

# A refusal line is about 200 bytes, and a run refuses at most its planned episodes.
_REFUSALS_CAP = ReadCap("a run's refusals file", 64)


@dataclass(frozen=True)
class Refusal:
    """One refused (episode, budget) of a run, with the reason."""

    agent_label: str
    task: str
    budget: int
    scene_id: str
    episode_id: str
    reason: str

    def key(self) -> tuple[str, str, int, str, str]:
        """The key its episode line would have (:func:`vlln.eval.results.record_key`)."""
        return (self.agent_label, self.task, self.budget, self.scene_id, self.episode_id)

    def describe(self) -> str:
        return f"{self.episode_id} ({self.scene_id}): {self.reason}"


def read_refusals(run_dir: Path) -> list[Refusal]:
    """The refusals of a run directory, each (episode, budget) once, in file order."""
    try:
        lines = _REFUSALS_CAP.read(run_dir / REFUSED_FILE).splitlines()
    except (FileNotFoundError, NotADirectoryError):
        return []
    found: dict[tuple[str, str, int, str, str], Refusal] = {}
    for line in lines:
        try:
            data = parse_json(line)
            refusal = Refusal(
                str(data["agent_label"]),
                str(data["task"]),
                int(data["budget"]),
                str(data["scene_id"]),
                str(data["episode_id"]),
                str(data["reason"]),
            )
        except (ValueError, TypeError, KeyError):
            continue
        found.setdefault(refusal.key(), refusal)
    return list(found.values())


def append_refusals(run_dir: Path, refusals: Iterable[Refusal]) -> None:
    """Add refusals to the run's file, durable before this returns."""
    text = "".join(json.dumps(asdict(refusal)) + "\n" for refusal in refusals)
    if not text:
        return
    path = run_dir / REFUSED_FILE
    with writing(path), path.open("a", encoding="utf-8") as handle:
        handle.write(text)
        handle.flush()
        os.fsync(handle.fileno())
