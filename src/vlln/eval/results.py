"""The results directory of one evaluation run, built so that nothing finished is ever lost.

Layout: :mod:`vlln.eval.run_dir`.

Each record is appended with one write, flushed and fsynced, so a kill loses at most the
episode in flight. That episode may leave a partial last line; reading for a restart cuts it
off (only when it is not a valid record: one that lacks just its newline is kept) and the
runner plays the episode again. Reading never fails on a line's content: a line that is not a
valid record (wrong JSON, a field of the wrong type or range) or repeats an episode is skipped
and named (file, line, field), and a resume moves it to ``episodes.skipped.jsonl``, so the
episode is played again and the results file keeps exactly one line per episode. A valid
line for an episode or budget outside the run's plan (:mod:`vlln.eval.plan`) is not counted
either, and a resume sets it aside too.
"""

from __future__ import annotations

import fcntl
import json
import os
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

from vlln.errors import ConfigError, DataFormatError
from vlln.eval.config import EvalConfig
from vlln.eval.plan import RunPlan, missing_shards
from vlln.eval.refusals import Refusal, read_refusals
from vlln.eval.run_dir import (
    EPISODES_FILE,
    LOCK_FILE,
    PLAN_FACT,
    PLANNED_FACT,
    PROVENANCE_FACT,
    RUN_FILE,
    SKIPPED_FILE,
    SUMMARY_JSON,
    SUMMARY_MD,
)
from vlln.files import (
    ReadCap,
    check_output_folder,
    parse_json,
    refuse_other_settings,
    write_bytes_atomic,
    write_text_atomic,
    writing,
)
from vlln.tasks.record import EpisodeRecord

RecordKey = tuple[str, str, int, str, str]

# A record line is about 3 kB and takes a few times that in memory once parsed: 256 MiB is
# some 80,000 episode lines; a bigger run may raise the cap.
RESULTS_CAP = ReadCap("a results file", 256, "VLLN_MAX_RESULTS_FILE_MB")
# run.json holds the arguments and the plan, one short entry per planned episode line.
_RUN_FILE_CAP = ReadCap("a run.json", 16)


def record_key(record: EpisodeRecord) -> RecordKey:
    """What makes an episode line unique: agent (with its detector), task, dialog budget,
    scene and episode."""
    return (record.agent_label, record.task, record.budget, record.scene_id, record.episode_id)


@dataclass(frozen=True)
class SkippedLine:
    """A line of a results file that holds no record to count, and why.

    ``kind``: ``invalid`` (not JSON, or a field of the wrong type or range), ``duplicate``
    (an episode already read from an earlier line), ``unplanned`` (an episode or budget the
    run does not plan), ``another run`` (a line of another agent, detector or task) or
    ``torn`` (a last line cut off by a kill).
    """

    file: Path
    line: int
    kind: str
    reason: str

    def describe(self) -> str:
        return f"{self.file}:{self.line}: {self.reason}"


@dataclass
class RecordScan:
    """What a results file holds: its valid records (first line of each episode), the lines
    skipped, and whether the last valid record lacks its newline."""

    records: list[EpisodeRecord] = field(default_factory=list)
    skipped: list[SkippedLine] = field(default_factory=list)
    lines: list[bytes] = field(default_factory=list)  # the records' lines, without newlines
    numbers: list[int] = field(default_factory=list)  # the records' line numbers
    skipped_lines: list[bytes] = field(default_factory=list)  # complete skipped lines
    newline_missing: bool = False


def scan_records(path: Path, max_steps: int | None = None) -> RecordScan:
    """Read every line of a results file; never raises on its content (module doc).
    ``max_steps``: the run's step cap, which no record may exceed (None: unknown)."""
    scan = RecordScan()
    try:
        data = RESULTS_CAP.read(path)
    except FileNotFoundError:
        return scan
    parts = data.split(b"\n")
    tail = parts.pop()  # after the last newline: empty, or a line never finished
    seen: dict[RecordKey, int] = {}
    for number, text in enumerate([*parts, tail], start=1):
        last = number == len(parts) + 1
        if not text.strip():
            continue
        try:
            record = _parse_line(text, max_steps)
        except DataFormatError as error:
            if last:
                reason = "partial last line (cut off by a stop); its episode is played again"
                scan.skipped.append(SkippedLine(path, number, "torn", reason))
            else:
                scan.skipped.append(SkippedLine(path, number, "invalid", str(error)))
                scan.skipped_lines.append(text)
            continue
        key = record_key(record)
        if key in seen:
            reason = (
                f"repeats the episode of line {seen[key]} (budget {key[2]}, {key[3]} {key[4]}); "
                "the first is counted"
            )
            scan.skipped.append(SkippedLine(path, number, "duplicate", reason))
            scan.skipped_lines.append(text)
            continue
        seen[key] = number
        scan.records.append(record)
        scan.lines.append(text)
        scan.numbers.append(number)
        scan.newline_missing = last
    return scan


def drop_unplanned(scan: RecordScan, plan: RunPlan, path: Path) -> None:
    """Move ``scan``'s records outside ``plan`` to its skipped lines: kind ``another run``
    for a line of another agent, detector or task, else ``unplanned``."""
    kept = [i for i, record in enumerate(scan.records) if plan.holds(record)]
    for index in sorted(set(range(len(scan.records))) - set(kept)):
        record = scan.records[index]
        where = f"episode {record.episode_id} ({record.scene_id}, budget {record.budget})"
        if plan.is_own(record):
            kind, reason = "unplanned", f"{where} is not in the run's plan; not counted"
        else:
            kind = "another run"
            reason = (
                f"{where} was played by {record.agent_label} on {record.task}, not by this "
                f"run's {plan.agent} on {plan.task}; not counted"
            )
        scan.skipped.append(SkippedLine(path, scan.numbers[index], kind, reason))
        scan.skipped_lines.append(scan.lines[index])
    scan.records = [scan.records[i] for i in kept]
    scan.lines = [scan.lines[i] for i in kept]
    scan.numbers = [scan.numbers[i] for i in kept]


def read_records(path: Path, repair: bool = False) -> list[EpisodeRecord]:
    """The valid records of a JSONL results file (see :func:`scan_records`).

    With ``repair`` the file is made to hold exactly those records, one per line: a torn last
    line is cut, a missing final newline is added, and invalid or repeated lines are moved to
    ``episodes.skipped.jsonl`` beside it, so nothing is deleted and nothing is counted twice.
    """
    scan = scan_records(path)
    if repair:
        repair_file(path, scan)
    return scan.records


def repair_file(path: Path, scan: RecordScan) -> None:
    """Make ``path`` hold exactly ``scan``'s records (see :func:`read_records`)."""
    with writing(path):
        _repair(path, scan)


def _repair(path: Path, scan: RecordScan) -> None:
    if scan.skipped_lines:
        with (path.parent / SKIPPED_FILE).open("ab") as handle:
            handle.write(b"".join(text + b"\n" for text in scan.skipped_lines))
            handle.flush()
            os.fsync(handle.fileno())
        write_bytes_atomic(path, b"".join(text + b"\n" for text in scan.lines))
        return
    if any(skipped.kind == "torn" for skipped in scan.skipped):
        with path.open("r+b") as handle:
            handle.truncate(RESULTS_CAP.read(path).rfind(b"\n") + 1)
            handle.flush()
            os.fsync(handle.fileno())
    elif scan.newline_missing:
        with path.open("ab") as handle:
            handle.write(b"\n")
            handle.flush()
            os.fsync(handle.fileno())


def _parse_line(line: bytes, max_steps: int | None) -> EpisodeRecord:
    try:
        data = parse_json(line)
    except DataFormatError as error:
        raise DataFormatError(f"not a JSON episode record ({str(error)[:120]})") from None
    if not isinstance(data, dict):
        raise DataFormatError(f"expected a JSON object, got {type(data).__name__}")
    record = EpisodeRecord.from_json(data)
    if max_steps is not None and record.steps > max_steps:
        raise DataFormatError(
            f"field 'steps' is {record.steps}, over the run's step cap of {max_steps}"
        )
    return record


class RecordWriter:
    """Appends records to a JSONL file, each one durable before :meth:`append` returns;
    ``records`` is everything in the file, those found at the start included."""

    def __init__(
        self, handle: IO[bytes], records: list[EpisodeRecord], skipped: list[SkippedLine]
    ) -> None:
        self._handle = handle
        self.records = records
        self.skipped = skipped  # lines the opening repair cut or set aside

    def append(self, record: EpisodeRecord) -> None:
        data = record.to_json()
        line = json.dumps(data, allow_nan=False, separators=(",", ":")) + "\n"
        # unbuffered, so a failed write leaves nothing to flush again; a resume cuts the
        # partial line it may leave
        with writing(Path(self._handle.name)):
            rest = memoryview(line.encode("utf-8"))
            while rest:
                rest = rest[self._handle.write(rest) or 0 :]
            os.fsync(self._handle.fileno())
        # keep what the file holds (distances rounded by to_json), so a summary made now
        # equals one recomputed from the file later
        self.records.append(EpisodeRecord.from_json(data))


class RunDirectory:
    """One run's directory: arguments, episode lines and summaries (layout: module doc)."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def check_is_directory(self) -> None:
        """A run directory that is a file, is under one or cannot be written is a one-line
        error before any work, not a traceback after it."""
        check_output_folder(self.path)

    @property
    def episodes_path(self) -> Path:
        return self.path / EPISODES_FILE

    @property
    def run_path(self) -> Path:
        return self.path / RUN_FILE

    def stored_run(self) -> dict[str, Any] | None:
        """``run.json`` as stored, or None for a fresh directory."""
        try:
            text = _RUN_FILE_CAP.read(self.run_path)
        except FileNotFoundError:
            return None
        try:
            data = parse_json(text)
        except DataFormatError as error:
            raise DataFormatError(
                f"{self.run_path}: {error}; restore it, or evaluate into another --out"
            ) from None
        if not isinstance(data, dict):
            raise DataFormatError(f"{self.run_path}: expected a JSON object of run arguments")
        return data

    def stored_config(self) -> EvalConfig | None:
        """The arguments the directory was started with, or None for a fresh directory."""
        data = self.stored_run()
        if data is None:
            return None
        return EvalConfig.from_json(data, str(self.run_path))

    def stored_scenes(self) -> str | None:
        """The folder of scanned scenes the run was made with (``--scenes``), if any."""
        try:
            scenes = (self.stored_run() or {}).get("scenes")
        except DataFormatError:
            return None
        return scenes if isinstance(scenes, str) else None

    def stored_planned(self) -> int | None:
        """Episode lines the run plans (None when its run.json predates the count)."""
        return _stored_count(self.stored_run(), PLANNED_FACT)

    def stored_max_steps(self) -> int | None:
        """The run's step cap (None for a folder without run.json, e.g. a web study)."""
        return _stored_count(self.stored_run(), "max_steps")

    def stored_plan(self) -> RunPlan | None:
        """The (episode, budget) pairs the run plans (None when its run.json predates it)."""
        config = self.stored_config()
        if config is None:
            return None
        return RunPlan.from_json((self.stored_run() or {}).get(PLAN_FACT), config)

    def prepare(
        self,
        config: EvalConfig,
        planned: int | None = None,
        provenance: dict[str, str | None] | None = None,
        plan: RunPlan | None = None,
    ) -> None:
        """Create the directory for ``config`` or check that it was started with it.

        ``run.json`` also records facts that are not arguments: ``planned_episodes`` and
        ``plan`` (so a reader can tell an incomplete run and the lines that belong to it) and
        ``provenance`` (agent, oracle, backend, model).
        """
        self.check_is_directory()
        if plan is not None:
            planned = plan.lines
        facts = {
            PLANNED_FACT: planned,
            PLAN_FACT: None if plan is None else plan.to_json(),
            PROVENANCE_FACT: provenance,
        }
        stored = self.stored_config()
        if stored is not None:
            recorded, wanted = stored.to_json(), config.to_json()
            stored_provenance = (self.stored_run() or {}).get(PROVENANCE_FACT)
            if stored_provenance is not None and provenance is not None:
                recorded[PROVENANCE_FACT], wanted[PROVENANCE_FACT] = stored_provenance, provenance
            refuse_other_settings(self.path, recorded, wanted, "a run")
            if any((self.stored_run() or {}).get(name) != value for name, value in facts.items()):
                self._write_run(config, facts)
            return
        if self.episodes_path.exists() and self.episodes_path.stat().st_size > 0:
            raise ConfigError(
                f"{self.episodes_path} exists but {self.run_path} does not, so it is unknown "
                "which run wrote it; use another --out"
            )
        self.path.mkdir(parents=True, exist_ok=True)
        self._write_run(config, facts)

    def _write_run(self, config: EvalConfig, facts: dict[str, Any]) -> None:
        data = config.to_json() | {
            name: value for name, value in facts.items() if value is not None
        }
        write_text_atomic(self.run_path, json.dumps(data, indent=2) + "\n")

    @contextmanager
    def writing(self, plan: RunPlan | None = None) -> Iterator[RecordWriter]:
        """Hold the directory's lock, cut a partial last line, set aside the lines outside
        ``plan`` (when given) and append to the episode file."""
        with (self.path / LOCK_FILE).open("w") as lock:
            try:
                fcntl.flock(lock.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                raise ConfigError(
                    f"another evaluation is writing to {self.path}; wait for it to end or "
                    "use another --out"
                ) from None
            scan = scan_records(self.episodes_path, self.stored_max_steps())
            if plan is not None:
                drop_unplanned(scan, plan, self.episodes_path)
            repair_file(self.episodes_path, scan)
            with self.episodes_path.open("ab", buffering=0) as handle:
                yield RecordWriter(handle, scan.records, scan.skipped)

    def records(self) -> list[EpisodeRecord]:
        return read_records(self.episodes_path)

    def write_summary(self, summary_json: dict[str, Any], summary_md: str) -> None:
        write_text_atomic(
            self.path / SUMMARY_JSON, json.dumps(summary_json, indent=2, allow_nan=False) + "\n"
        )
        write_text_atomic(self.path / SUMMARY_MD, summary_md)


@dataclass
class RunContents:
    """The records of one or more run directories and what reading them found: lines skipped,
    lines set aside by a resume, the episode lines the runs planned (None if unknown), those
    of shards not read included, which shards those are, and the episodes they refused
    (:mod:`vlln.eval.refusals`)."""

    records: list[EpisodeRecord] = field(default_factory=list)
    skipped: list[SkippedLine] = field(default_factory=list)
    set_aside: int = 0
    planned: int | None = 0
    refused: list[Refusal] = field(default_factory=list)
    missing_shards: list[str] = field(default_factory=list)

    def skipped_kinds(self) -> list[tuple[str, str]]:
        """(kind, description) of every line not counted, set-aside lines included."""
        found = [(line.kind, line.describe()) for line in self.skipped]
        return found + [(f"set aside in {SKIPPED_FILE}", "")] * self.set_aside


def load_runs(paths: Iterable[Path], whole: bool = True) -> RunContents:
    """Everything in several run directories (or JSONL files), e.g. the shards of one run.

    The same episode in two places is an error: merging would count it twice. Lines outside
    a run's plan are skipped (kind ``unplanned``). With ``whole`` (reading results, rather
    than one shard reading itself) shards of a run that were not passed are named, and their
    planned lines counted as not finished.
    """
    contents = RunContents()
    origin: dict[RecordKey, Path] = {}
    runs: list[tuple[EvalConfig, RunPlan | None]] = []
    for path in paths:
        if path.exists() and not path.is_dir() and path.suffix != ".jsonl":
            raise ConfigError(f"{path} is a file; pass a run directory of vlln eval")
        file = path / EPISODES_FILE if path.is_dir() else path
        if not file.exists():
            raise ConfigError(f"{path} holds no {EPISODES_FILE}; pass a run directory of vlln eval")
        run = RunDirectory(path) if path.is_dir() else None
        scan = scan_records(file, None if run is None else run.stored_max_steps())
        config = None if run is None else run.stored_config()
        plan = None if run is None else run.stored_plan()
        if plan is not None:
            drop_unplanned(scan, plan, file)
        for record in scan.records:
            key = record_key(record)
            if key in origin:
                raise ConfigError(
                    f"episode {key[4]} ({key[3]}, budget {key[2]}) is in both {origin[key]} and "
                    f"{file}; pass disjoint shards or runs"
                )
            origin[key] = file
            contents.records.append(record)
        contents.skipped += scan.skipped
        aside = file.parent / SKIPPED_FILE
        if aside.is_file():
            with aside.open("rb") as handle:  # by blocks: the file is never read whole
                blocks = iter(lambda: handle.read(1 << 20), b"")
                contents.set_aside += sum(block.count(b"\n") for block in blocks)
        if path.is_dir():
            contents.refused += read_refusals(path)
        planned = plan.lines if plan is not None else None if run is None else run.stored_planned()
        if planned is None or contents.planned is None:
            contents.planned = None
        else:
            contents.planned += planned
        if config is not None and whole:
            runs.append((config, plan))
    contents.missing_shards, absent_lines = missing_shards(runs)
    if contents.missing_shards:
        if absent_lines is None or contents.planned is None:
            contents.planned = None
        else:
            contents.planned += absent_lines
    return contents


def _stored_count(run: dict[str, Any] | None, name: str) -> int | None:
    value = (run or {}).get(name)
    return value if isinstance(value, int) and not isinstance(value, bool) else None


def load_run_records(paths: Iterable[Path]) -> list[EpisodeRecord]:
    """The valid records of :func:`load_runs`."""
    return load_runs(paths).records
