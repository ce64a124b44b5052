"""Which episodes get videos, and writing them: ``vlln video`` and the report's videos.

A source is a run directory, a results file (JSON Lines) or one record (a JSON file). Without
a named episode, dialog episodes come first (most answered questions, then most questions),
at the largest budget, so a video shows the dialog when there is one. A scanned scene is read
from the folder the run was made with (``--scenes`` in its ``run.json``) unless another is
given.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

from vlln.errors import ConfigError, DataFormatError
from vlln.eval.results import RESULTS_CAP, RunDirectory, load_run_records
from vlln.eval.video import VideoConfig, write_episode_video
from vlln.files import parse_json
from vlln.sim.simulator import Simulator
from vlln.tasks.episode import scene_name
from vlln.tasks.record import EpisodeRecord
from vlln.tasks.scenes import is_procedural, scene_house

_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def read_video_source(path: Path) -> list[EpisodeRecord]:
    """The records of a run directory, a JSON Lines results file or a single JSON record."""
    if path.suffix == ".json" and path.is_file():
        try:
            return [EpisodeRecord.from_json(parse_json(RESULTS_CAP.read(path)))]
        except DataFormatError as error:
            raise DataFormatError(f"{path} is not a JSON episode record: {error}") from None
    if not path.exists():
        raise ConfigError(f"{path} does not exist; give a run directory or a results file")
    return load_run_records([path])


def dialog_first(records: Sequence[EpisodeRecord], count: int) -> list[EpisodeRecord]:
    """Up to ``count`` records at the largest budget, those with the most dialog first."""
    if not records:
        return []
    top = max(record.budget for record in records)
    pool = [record for record in records if record.budget == top]
    ranked = sorted(
        pool,
        key=lambda r: (-sum(t.answered for t in r.dialog), -len(r.dialog), r.episode_id),
    )
    return ranked[:count]


def replayable(record: EpisodeRecord, scenes: str | Path | None = None) -> bool:
    """Whether the record's house can be rebuilt here: a built-in procedural house, or a
    scanned scene in the folder ``scenes``."""
    if not record.positions:
        return False
    if is_procedural(record.scene_id):
        return True
    return scenes is not None and (Path(scenes) / scene_name(record.scene_id)).is_dir()


def scenes_of(source: Path) -> str | None:
    """The ``--scenes`` folder a run was made with: from ``run.json`` of the run directory
    ``source`` (or of the folder holding the results file ``source``)."""
    return RunDirectory(source if source.is_dir() else source.parent).stored_scenes()


def video_name(record: EpisodeRecord, prefix: str = "video") -> str:
    return _UNSAFE.sub("_", f"{prefix}_{record.episode_id}_b{record.budget}.mp4")


def write_videos(
    records: Sequence[EpisodeRecord],
    out: Path,
    config: VideoConfig | None = None,
    prefix: str = "video",
    scenes: str | Path | None = None,
) -> list[tuple[Path, float]]:
    """One MP4 per record in folder ``out`` (scanned scenes read from ``scenes``); returns
    (file, seconds) for each."""
    config = config or VideoConfig()
    written: list[tuple[Path, float]] = []
    for record in records:
        house = scene_house(record.scene_id, scenes)
        with Simulator(house) as sim:
            path = out / video_name(record, prefix)
            written.append((path, write_episode_video(record, house, sim, path, config)))
    return written


def make_video(
    source: Path,
    out: Path | None,
    episode: str | None,
    budget: int | None,
    scenes: Path | None,
) -> tuple[Path, float]:
    """``vlln video``: one episode of ``source`` (named, or the first with dialog); scanned
    scenes come from ``scenes`` or the run's own ``--scenes``."""
    records = read_video_source(source)
    if episode is not None:
        records = [r for r in records if r.episode_id == episode]
    if budget is not None:
        records = [r for r in records if r.budget == budget]
    chosen = dialog_first(records, 1)
    if not chosen:
        raise ConfigError(
            f"{source} has no episode matching episode={episode} budget={budget}; "
            "leave them out to take the episode with the most dialog"
        )
    record = chosen[0]
    folder = out.parent if out else (source if source.is_dir() else source.parent) / "videos"
    [(path, seconds)] = write_videos([record], folder, scenes=scenes or scenes_of(source))
    if out is not None and path != out:
        path = path.replace(out)
    return path, seconds
