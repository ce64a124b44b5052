"""``vlln data export-sft``: a trajectory dataset as multi-image, multi-turn conversations.

::

    <out>/sft.jsonl        one sample per line, in house, episode and frame order:
                           {"id", "images": [paths in <image> order], "conversations":
                            [{"from": "human" | "gpt", "value": ...}, ...]}
    <out>/images/<house>/episode_<i>/{level,down}_<frame>.jpg
    <out>/export.json      format, settings, houses and counts; written last, so its presence
                           marks a complete export

Images are written plainly, ``sft.jsonl`` through a temporary file and a rename, and
``export.json`` (removed first when an earlier export is overwritten) atomically at the end: a
killed export leaves a folder without ``export.json`` that a rerun overwrites. The output
depends only on the dataset and the settings: the same input gives the same bytes.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from tqdm import tqdm

from vlln import __version__
from vlln.datagen.layout import HouseDataset
from vlln.datagen.sft.config import SftConfig
from vlln.datagen.sft.conversation import Sample, build_samples
from vlln.datagen.sft.decisions import Decision, ForwardStep, PixelGoal, Stop, cut_decisions
from vlln.datagen.sft.dialog import apply_budget
from vlln.datagen.sft.images import IMAGES_DIR, ImageStore
from vlln.datagen.sft.pixel_goals import GoalLocator
from vlln.datagen.sft.source import SourceTrajectory, down_camera, open_houses, read_trajectories
from vlln.errors import ConfigError, DataFormatError
from vlln.files import write_text_atomic
from vlln.sim.camera import CameraSpec

FORMAT_VERSION = "vlln-sft/1.0"
SFT_FILE = "sft.jsonl"
SUMMARY_FILE = "export.json"
_OWN_ENTRIES = {SFT_FILE, SUMMARY_FILE, IMAGES_DIR}


@dataclass
class SftSummary:
    """What an export wrote (also the ``counts`` of ``export.json``)."""

    out_dir: Path
    trajectories: int = 0
    samples: int = 0
    images: int = 0
    refused_questions: int = 0
    decisions: dict[str, int] = field(
        default_factory=lambda: {"talk": 0, "move": 0, "forward": 0, "turn": 0, "stop": 0}
    )

    def counts(self) -> dict[str, Any]:
        return {
            "trajectories": self.trajectories,
            "samples": self.samples,
            "images": self.images,
            "refused_questions": self.refused_questions,
            "decisions": dict(self.decisions),
        }


def export_sft(
    dataset_root: str | Path,
    out_dir: str | Path,
    config: SftConfig | None = None,
    progress: bool = True,
) -> SftSummary:
    """Export every kept trajectory of a built dataset into ``out_dir``."""
    config = config or SftConfig()
    houses = open_houses(dataset_root)
    out = Path(out_dir)
    _prepare_out(out)
    store = ImageStore(out, config.image_size, config.jpeg_quality)
    summary = SftSummary(out)
    bar = tqdm(
        total=sum(len(house.episodes) for house in houses),
        desc="export-sft",
        unit="traj",
        disable=not progress,
    )
    with bar, _lines_atomic(out / SFT_FILE) as sink:
        for house in houses:
            spec = down_camera(house)
            for trajectory in read_trajectories(house):
                try:
                    for sample in _samples(house, spec, trajectory, config, summary):
                        index = trajectory.episode_index
                        paths = [store.add(house, index, ref) for ref in sample.images]
                        sink.write(_sample_line(trajectory, sample, paths))
                except FileNotFoundError as error:
                    raise DataFormatError(
                        f"{house.root}, episode {trajectory.episode_index}: {error}; the "
                        "dataset is incomplete: rebuild that house with `vlln data build`"
                    ) from error
                summary.trajectories += 1
                bar.update()
    summary.images = len(store.written)
    document = {
        "format_version": FORMAT_VERSION,
        "vlln_version": __version__,
        "files": {"conversations": SFT_FILE, "images": f"{IMAGES_DIR}/"},
        "settings": config.settings(),
        "houses": [house.root.name for house in houses],
        "counts": summary.counts(),
    }
    write_text_atomic(out / SUMMARY_FILE, json.dumps(document, indent=2) + "\n")
    return summary


def _samples(
    house: HouseDataset,
    spec: CameraSpec,
    trajectory: SourceTrajectory,
    config: SftConfig,
    summary: SftSummary,
) -> list[Sample]:
    """The trajectory's samples; counts its decisions into ``summary``."""
    index = trajectory.episode_index
    locator = GoalLocator(
        spec,
        trajectory.feet,
        trajectory.down_eyes,
        trajectory.down_rotations,
        lambda frame: house.depth("down", index, frame),
        config.depth_tolerance,
    )
    exchanges = apply_budget(trajectory.exchanges, config.budget)
    decisions = cut_decisions(
        trajectory.actions,
        trajectory.feet,
        exchanges,
        locator,
        config.max_turn_run,
        config.max_goal_steps,
    )
    _count(decisions, summary)
    return build_samples(trajectory.category, decisions, exchanges, config.history_frames)


def _count(decisions: list[Decision], summary: SftSummary) -> None:
    counts = summary.decisions
    for decision in decisions:
        counts["talk"] += len(decision.talks)
        summary.refused_questions += sum(talk.refused for talk in decision.talks)
        move = decision.move
        if isinstance(move, PixelGoal):
            counts["move"] += 1
        elif isinstance(move, ForwardStep):
            counts["forward"] += 1
        elif isinstance(move, Stop):
            counts["stop"] += 1
        else:
            counts["turn"] += 1
    summary.samples += len(decisions)


def _sample_line(trajectory: SourceTrajectory, sample: Sample, paths: list[str]) -> str:
    record = {
        "id": f"{trajectory.house}/episode_{trajectory.episode_index:06d}/frame_{sample.frame:06d}",
        "images": paths,
        "conversations": [{"from": turn.speaker, "value": turn.value} for turn in sample.turns],
    }
    return json.dumps(record, ensure_ascii=False) + "\n"


def _prepare_out(out: Path) -> None:
    """Make ``out`` ready: new, empty, or an earlier export (whose output is removed)."""
    if out.exists() and not out.is_dir():
        raise ConfigError(f"{out} exists and is not a folder; choose a folder for the export")
    out.mkdir(parents=True, exist_ok=True)
    entries = {entry.name for entry in out.iterdir()}
    foreign = sorted(name for name in entries - _OWN_ENTRIES if not name.startswith("."))
    if foreign:
        shown = ", ".join(foreign[:5])
        raise ConfigError(
            f"{out} holds files that are not an export ({shown}); choose an empty or new "
            "folder, or one an earlier export wrote"
        )
    (out / SUMMARY_FILE).unlink(missing_ok=True)
    shutil.rmtree(out / IMAGES_DIR, ignore_errors=True)


@contextmanager
def _lines_atomic(path: Path) -> Iterator[IO[str]]:
    """A text file written through a temporary file renamed into place once complete."""
    fd, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        os.chmod(temp, 0o644)
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
