"""The results directory of one evaluation run, built so that nothing finished is ever lost.

Layout::

    DIR/run.json        the run's arguments (EvalConfig); a restart must match them
    DIR/episodes.jsonl  one EpisodeRecord.to_json() per line, in the order they finished
    DIR/summary.json    every metric, recomputed from episodes.jsonl (see vlln.eval.summary)
    DIR/summary.md      the same as Markdown tables
    DIR/.lock           held while a process writes here, so two runs cannot interleave

Each record is appended with one write, flushed and fsynced, so a kill loses at most the
episode in flight. That episode may leave a partial last line without its newline; reading
for a restart cuts it off and the runner plays the episode again. A malformed *complete* line
is not a crash artefact (someone edited the file), so it is a :class:`DataFormatError`.
"""

from __future__ import annotations

import fcntl
import json
import os
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from vlln.errors import ConfigError, DataFormatError
from vlln.eval.config import EvalConfig, describe_differences
from vlln.files import write_text_atomic
from vlln.tasks.record import EpisodeRecord

RUN_FILE = "run.json"
EPISODES_FILE = "episodes.jsonl"
SUMMARY_JSON = "summary.json"
SUMMARY_MD = "summary.md"
LOCK_FILE = ".lock"

RecordKey = tuple[str, str, int, str, str]


def record_key(record: EpisodeRecord) -> RecordKey:
    """What makes an episode line unique: agent (with its detector), task, dialog budget,
    scene and episode."""
    return (record.agent_label, record.task, record.budget, record.scene_id, record.episode_id)


def read_records(path: Path, repair: bool = False) -> list[EpisodeRecord]:
    """The records of a JSONL results file, ignoring a partial last line.

    With ``repair`` the partial line is also cut off the file, so the next append starts on a
    fresh line. A missing file holds no records.
    """
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return []
    complete_end = data.rfind(b"\n") + 1
    if repair and complete_end < len(data):
        with path.open("r+b") as handle:
            handle.truncate(complete_end)
            handle.flush()
            os.fsync(handle.fileno())
    records: list[EpisodeRecord] = []
    seen: dict[RecordKey, int] = {}
    for number, line in enumerate(data[:complete_end].split(b"\n")[:-1], start=1):
        record = _parse_line(line, f"{path}:{number}")
        key = record_key(record)
        if key in seen:
            raise DataFormatError(
                f"{path}:{number} repeats the episode of line {seen[key]} "
                f"(budget {key[2]}, {key[3]} {key[4]}); two runs wrote into one file or it was "
                "edited; keep one of the lines"
            )
        seen[key] = number
        records.append(record)
    return records


def _parse_line(line: bytes, where: str) -> EpisodeRecord:
    try:
        data = json.loads(line.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise DataFormatError(f"{where}: not a JSON episode record ({error})") from None
    if not isinstance(data, dict):
        raise DataFormatError(f"{where}: expected a JSON object, got {type(data).__name__}")
    try:
        return EpisodeRecord.from_json(data)
    except DataFormatError as error:
        raise DataFormatError(f"{where}: {error}") from None


class RecordWriter:
    """Appends records to a JSONL file, each one durable before :meth:`append` returns;
    ``records`` is everything in the file, those found at the start included."""

    def __init__(self, handle: IO[bytes], records: list[EpisodeRecord]) -> None:
        self._handle = handle
        self.records = records

    def append(self, record: EpisodeRecord) -> None:
        data = record.to_json()
        line = json.dumps(data, allow_nan=False, separators=(",", ":")) + "\n"
        self._handle.write(line.encode("utf-8"))
        self._handle.flush()
        os.fsync(self._handle.fileno())
        # keep what the file holds (distances rounded by to_json), so a summary made now
        # equals one recomputed from the file later
        self.records.append(EpisodeRecord.from_json(data))


class RunDirectory:
    """One run's directory: arguments, episode lines and summaries (layout: module doc)."""

    def __init__(self, path: Path) -> None:
        self.path = path

    @property
    def episodes_path(self) -> Path:
        return self.path / EPISODES_FILE

    @property
    def run_path(self) -> Path:
        return self.path / RUN_FILE

    def stored_config(self) -> EvalConfig | None:
        """The arguments the directory was started with, or None for a fresh directory."""
        try:
            text = self.run_path.read_text(encoding="utf-8")
        except FileNotFoundError:
            return None
        try:
            data = json.loads(text)
        except json.JSONDecodeError as error:
            raise DataFormatError(f"{self.run_path} is not JSON ({error})") from None
        return EvalConfig.from_json(data, str(self.run_path))

    def prepare(self, config: EvalConfig) -> None:
        """Create the directory for ``config`` or check that it was started with it."""
        stored = self.stored_config()
        if stored is not None:
            differences = describe_differences(stored, config)
            if differences:
                raise ConfigError(
                    f"{self.path} holds a run with other arguments ("
                    + "; ".join(differences)
                    + "). Use another --out, or the same arguments to resume it"
                )
            return
        if self.episodes_path.exists() and self.episodes_path.stat().st_size > 0:
            raise ConfigError(
                f"{self.episodes_path} exists but {self.run_path} does not, so it is unknown "
                "which run wrote it; use another --out"
            )
        self.path.mkdir(parents=True, exist_ok=True)
        write_text_atomic(self.run_path, json.dumps(config.to_json(), indent=2) + "\n")

    @contextmanager
    def writing(self) -> Iterator[RecordWriter]:
        """Hold the directory's lock, cut a partial last line and append to the episode file."""
        with (self.path / LOCK_FILE).open("w") as lock:
            try:
                fcntl.flock(lock.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                raise ConfigError(
                    f"another evaluation is writing to {self.path}; wait for it to end or "
                    "use another --out"
                ) from None
            found = read_records(self.episodes_path, repair=True)
            with self.episodes_path.open("ab") as handle:
                yield RecordWriter(handle, found)

    def records(self) -> list[EpisodeRecord]:
        return read_records(self.episodes_path)

    def write_summary(self, summary_json: dict[str, Any], summary_md: str) -> None:
        write_text_atomic(
            self.path / SUMMARY_JSON, json.dumps(summary_json, indent=2, allow_nan=False) + "\n"
        )
        write_text_atomic(self.path / SUMMARY_MD, summary_md)


def load_run_records(paths: Iterable[Path]) -> list[EpisodeRecord]:
    """All records of several run directories (or JSONL files), e.g. the shards of one run.

    The same episode in two places is an error: merging would count it twice.
    """
    merged: list[EpisodeRecord] = []
    origin: dict[RecordKey, Path] = {}
    for path in paths:
        file = path / EPISODES_FILE if path.is_dir() else path
        if not file.exists():
            raise ConfigError(f"{path} holds no {EPISODES_FILE}; pass a run directory of vlln eval")
        for record in read_records(file):
            key = record_key(record)
            if key in origin:
                raise ConfigError(
                    f"episode {key[4]} ({key[3]}, budget {key[2]}) is in both {origin[key]} and "
                    f"{file}; pass disjoint shards or runs"
                )
            origin[key] = file
            merged.append(record)
    return merged
