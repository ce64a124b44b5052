"""Counting a built trajectory dataset: yield, rejections, lengths, dialogs, targets.

Every number comes from the files a build leaves behind, so the statistics can be taken of a
dataset built elsewhere, or while a build still runs: finished houses (``meta/info.json``
present) are counted in full, unfinished ones only as "in progress" from their journal, which
is read without being touched. A dialog turn is one navigator question and the oracle's answer
to it; words are whitespace-separated tokens.
"""

from __future__ import annotations

import statistics
from collections import Counter
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from vlln.datagen.layout import (
    EPISODES_DIR,
    HOUSE_LINES_CAP,
    INFO_FILE,
    JOURNAL_FILE,
    TRAJECTORIES_DIR,
    is_finished,
)
from vlln.datagen.reader import HouseDataset, house_folders
from vlln.datagen.stats.episodes import EpisodeStageStats, read_episode_stage
from vlln.errors import DataFormatError
from vlln.files import parse_json


@dataclass(frozen=True)
class IntDistribution:
    """How often each whole-number value occurs (step counts, turns, words)."""

    counts: dict[int, int]

    @staticmethod
    def of(values: list[int]) -> IntDistribution:
        return IntDistribution(dict(sorted(Counter(values).items())))

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def values(self) -> list[int]:
        """Every observation, in increasing order."""
        return [value for value, count in self.counts.items() for _ in range(count)]

    @property
    def mean(self) -> float | None:
        if not self.total:
            return None
        return sum(value * count for value, count in self.counts.items()) / self.total

    @property
    def median(self) -> float | None:
        return float(statistics.median(self.values())) if self.total else None

    def to_json(self) -> dict[str, Any]:
        return {
            "n": self.total,
            "mean": _rounded(self.mean),
            "median": self.median,
            "min": min(self.counts) if self.counts else None,
            "max": max(self.counts) if self.counts else None,
            "counts": {str(value): count for value, count in self.counts.items()},
        }


@dataclass(frozen=True)
class HouseProgress:
    """An unfinished house folder: attempts logged so far and how many were kept."""

    house: str
    attempted: int
    kept: int


@dataclass(frozen=True)
class DatasetStats:
    """The statistics of one dataset folder (finished houses only, plus what is in progress)."""

    root: str
    houses: int
    attempted: int
    kept: int
    rejections: dict[str, int]
    frames: int
    steps: IntDistribution
    path_lengths: list[float]  # metres walked, one per trajectory
    dialog_turns: IntDistribution  # turns per trajectory
    question_words: IntDistribution
    answer_words: IntDistribution
    question_types: dict[str, int]  # by the oracle's classification of the question
    triggers: dict[str, int]  # by why the collector asked
    trigger_question_types: dict[str, dict[str, int]]  # trigger -> question type -> turns
    target_categories: dict[str, int]  # most frequent first
    episodes_per_house: dict[str, int]
    in_progress: list[HouseProgress] = field(default_factory=list)
    episode_stage: list[EpisodeStageStats] = field(default_factory=list)

    @property
    def trajectories(self) -> int:
        return self.kept

    @property
    def yield_rate(self) -> float | None:
        """Kept over attempted trajectories (None before any attempt)."""
        return self.kept / self.attempted if self.attempted else None

    def rejection_shares(self) -> dict[str, float]:
        """Each reason's share of the attempted trajectories."""
        return {r: n / self.attempted for r, n in self.rejections.items() if self.attempted}

    @property
    def turns(self) -> int:
        return self.question_words.total

    @property
    def path_length_mean(self) -> float | None:
        return statistics.fmean(self.path_lengths) if self.path_lengths else None

    @property
    def path_length_median(self) -> float | None:
        return float(statistics.median(self.path_lengths)) if self.path_lengths else None

    def to_json(self) -> dict[str, Any]:
        shares = self.rejection_shares()
        return {
            "root": self.root,
            "houses": self.houses,
            "houses_in_progress": [asdict(house) for house in self.in_progress],
            "attempted": self.attempted,
            "kept": self.kept,
            "yield": _rounded(self.yield_rate),
            "rejections": {
                reason: {"count": count, "share": _rounded(shares.get(reason))}
                for reason, count in self.rejections.items()
            },
            "trajectories": self.trajectories,
            "frames": self.frames,
            "steps": self.steps.to_json(),
            "path_length_m": {
                "mean": _rounded(self.path_length_mean),
                "median": _rounded(self.path_length_median),
            },
            "dialog_turns": {"total": self.turns, **self.dialog_turns.to_json()},
            "words_per_turn": {
                "question": self.question_words.to_json(),
                "answer": self.answer_words.to_json(),
            },
            "question_types": self.question_types,
            "triggers": self.triggers,
            "trigger_question_types": self.trigger_question_types,
            "target_categories": self.target_categories,
            "episodes_per_house": self.episodes_per_house,
            "episode_stage": [stage.to_json() for stage in self.episode_stage],
        }


def dataset_stats(root: str | Path) -> DatasetStats:
    """Count every house folder under ``<root>/trajectories`` and the episode-stage files."""
    base = Path(root)
    if not base.is_dir():
        raise DataFormatError(f"{base} is not a folder; give the folder `vlln data build` wrote")
    folders = list(house_folders(base))
    if not folders:
        raise DataFormatError(
            f"{base} has no house folders under {TRAJECTORIES_DIR}/; is it a dataset built by "
            "`vlln data build` (run the build first)?"
        )
    tally = _Tally()
    in_progress: list[HouseProgress] = []
    for folder in folders:
        if is_finished(folder):
            tally.add_house(HouseDataset(folder))
        else:
            in_progress.append(_progress(folder))
    return tally.finish(str(base), in_progress, read_episode_stage(base / EPISODES_DIR))


@dataclass
class _Tally:
    """Running counts over the finished houses."""

    houses: int = 0
    attempted: int = 0
    frames: int = 0
    rejections: Counter[str] = field(default_factory=Counter)
    lengths: list[int] = field(default_factory=list)
    path_lengths: list[float] = field(default_factory=list)
    turns: list[int] = field(default_factory=list)
    question_words: list[int] = field(default_factory=list)
    answer_words: list[int] = field(default_factory=list)
    question_types: Counter[str] = field(default_factory=Counter)
    triggers: Counter[str] = field(default_factory=Counter)
    pairs: Counter[tuple[str, str]] = field(default_factory=Counter)
    categories: Counter[str] = field(default_factory=Counter)
    per_house: dict[str, int] = field(default_factory=dict)

    def add_house(self, house: HouseDataset) -> None:
        info_path = house.root / INFO_FILE
        try:
            attempted = int(house.info["attempted"])
            rejections = {str(k): int(v) for k, v in house.info["rejections"].items()}
            total_episodes = int(house.info["total_episodes"])
        except (KeyError, TypeError, ValueError, AttributeError) as error:
            raise DataFormatError(
                f"{info_path}: missing or malformed attempted/rejections/total_episodes "
                f"({error!r}); rebuild the house"
            ) from error
        if total_episodes != len(house.episodes) or attempted != len(house.episodes) + sum(
            rejections.values()
        ):
            raise DataFormatError(
                f"{info_path}: {attempted} attempted and {total_episodes} kept do not match "
                f"{len(house.episodes)} episodes.jsonl rows and {sum(rejections.values())} "
                "rejections; the folder was edited or damaged: delete it and rebuild"
            )
        self.houses += 1
        self.attempted += attempted
        self.rejections.update(rejections)
        self.per_house[house.root.name] = len(house.episodes)
        for row in house.episodes:
            self._add_episode(row, house.root)

    def _add_episode(self, row: dict[str, Any], folder: Path) -> None:
        where = f"{folder / 'meta' / 'episodes.jsonl'} episode {row.get('episode_index')}"
        try:
            length = int(row["length"])
            self.path_lengths.append(float(row["path_length"]))
            self.categories[str(row["target"]["category"])] += 1
            dialogs = list(row["dialogs"])
        except (KeyError, TypeError, ValueError) as error:
            raise DataFormatError(f"{where}: missing or malformed field {error}") from error
        self.lengths.append(length)
        self.frames += length
        self.turns.append(self._add_dialog(dialogs, where))

    def _add_dialog(self, dialogs: list[dict[str, Any]], where: str) -> int:
        """Count one trajectory's turns; each navigator row must be followed by its answer."""
        if len(dialogs) % 2:
            raise DataFormatError(f"{where}: {len(dialogs)} dialog rows, not question-answer pairs")
        for question, answer in zip(dialogs[::2], dialogs[1::2], strict=True):
            roles = (question.get("role"), answer.get("role"))
            if roles != ("navigator", "oracle"):
                raise DataFormatError(
                    f"{where}: dialog rows must alternate navigator, oracle; got {roles}"
                )
            trigger = str(question.get("trigger"))
            kind = str(answer.get("question_type"))
            self.question_words.append(len(str(question.get("message", "")).split()))
            self.answer_words.append(len(str(answer.get("message", "")).split()))
            self.triggers[trigger] += 1
            self.question_types[kind] += 1
            self.pairs[(trigger, kind)] += 1
        return len(dialogs) // 2

    def finish(
        self, root: str, in_progress: list[HouseProgress], stage: list[EpisodeStageStats]
    ) -> DatasetStats:
        by_trigger: dict[str, dict[str, int]] = {}
        for (trigger, kind), count in sorted(self.pairs.items()):
            by_trigger.setdefault(trigger, {})[kind] = count
        return DatasetStats(
            root=root,
            houses=self.houses,
            attempted=self.attempted,
            kept=len(self.lengths),
            rejections=_by_count(self.rejections),
            frames=self.frames,
            steps=IntDistribution.of(self.lengths),
            path_lengths=self.path_lengths,
            dialog_turns=IntDistribution.of(self.turns),
            question_words=IntDistribution.of(self.question_words),
            answer_words=IntDistribution.of(self.answer_words),
            question_types=_by_count(self.question_types),
            triggers=_by_count(self.triggers),
            trigger_question_types=by_trigger,
            target_categories=_by_count(self.categories),
            episodes_per_house=self.per_house,
            in_progress=in_progress,
            episode_stage=stage,
        )


def _progress(folder: Path) -> HouseProgress:
    """Attempts in an unfinished house's journal; a torn last line (a write under way) is
    skipped, and the file is only read, never repaired, since a build may be writing it."""
    journal = folder / JOURNAL_FILE
    attempts: dict[str, bool] = {}
    if journal.exists():
        for line in HOUSE_LINES_CAP.read(journal).splitlines():
            try:
                data = parse_json(line)
                attempts[str(data["episode_id"])] = data["episode_index"] is not None
            except (ValueError, KeyError, TypeError):
                continue
    return HouseProgress(folder.name, len(attempts), sum(attempts.values()))


def _by_count(counter: Counter[str]) -> dict[str, int]:
    """Most frequent first, ties by name, so the files are the same from run to run."""
    return dict(sorted(counter.items(), key=lambda item: (-item[1], item[0])))


def _rounded(value: float | None) -> float | None:
    return None if value is None else round(value, 4)
