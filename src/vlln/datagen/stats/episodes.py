"""The episode stage of a dataset: what ``<root>/episodes/<split>_stats.json`` records.

Episode generation (:mod:`vlln.tasks.generation`) writes one statistics file per split, with
split totals and one entry per house; this module reads the parts the dataset statistics
report: episodes per house and per target category, skipped targets and distractors per target.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vlln.datagen.layout import house_dir_name
from vlln.errors import DataFormatError
from vlln.files import parse_json
from vlln.tasks.split_files import STATS_CAP

STATS_SUFFIX = "_stats.json"


@dataclass(frozen=True)
class EpisodeStageStats:
    """One split's episode statistics (counts per task: the IIGN, IGN and ObjectNav lists are
    aligned one to one)."""

    split: str
    houses: int
    instances: int
    targets_used: int
    episodes: int
    skipped: dict[str, int]
    distractors_per_target: dict[int, int]  # same-category other instances -> targets
    episodes_per_category: dict[str, int]
    episodes_per_house: dict[str, int]
    mean_start_distance: float

    @property
    def mean_distractors(self) -> float | None:
        targets = sum(self.distractors_per_target.values())
        if not targets:
            return None
        weighted = sum(k * n for k, n in self.distractors_per_target.items())
        return weighted / targets

    def to_json(self) -> dict[str, Any]:
        mean = self.mean_distractors
        return {
            "split": self.split,
            "houses": self.houses,
            "instances": self.instances,
            "targets_used": self.targets_used,
            "episodes": self.episodes,
            "skipped": self.skipped,
            "distractors_per_target": {str(k): n for k, n in self.distractors_per_target.items()},
            "mean_distractors": None if mean is None else round(mean, 4),
            "episodes_per_category": self.episodes_per_category,
            "episodes_per_house": self.episodes_per_house,
            "mean_start_distance": self.mean_start_distance,
        }


def read_episode_stage(episodes_dir: Path) -> list[EpisodeStageStats]:
    """Every ``<split>_stats.json`` in ``episodes_dir``, by split name; none if it is absent."""
    if not episodes_dir.is_dir():
        return []
    paths = sorted(episodes_dir.glob(f"*{STATS_SUFFIX}"))
    return [_read(path) for path in paths]


def _read(path: Path) -> EpisodeStageStats:
    try:
        document = parse_json(STATS_CAP.read(path))
        totals = document["totals"]
        return EpisodeStageStats(
            split=path.name[: -len(STATS_SUFFIX)],
            houses=int(totals["houses"]),
            instances=int(totals["instances"]),
            targets_used=int(totals["targets_used"]),
            episodes=int(totals["episodes"]),
            skipped={str(k): int(v) for k, v in totals["skipped"].items()},
            distractors_per_target={
                int(k): int(v) for k, v in totals["distractors_per_target"].items()
            },
            episodes_per_category={
                str(k): int(v) for k, v in totals["episodes_per_category"].items()
            },
            episodes_per_house={
                house_dir_name(str(h["scene_id"])): int(h["episodes"]) for h in document["houses"]
            },
            mean_start_distance=float(totals["mean_start_distance"]),
        )
    except (ValueError, KeyError, TypeError, AttributeError) as error:
        raise DataFormatError(
            f"{path}: not an episode statistics file ({error!r}); rebuild the episodes with "
            "`vlln data build` or remove the file"
        ) from error
