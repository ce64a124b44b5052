"""A session's journal: its settings and every action, on disk as they happen.

``DIR/sessions/<session_id>.jsonl`` holds one JSON object per line: the session's settings
first, then one line per action or question (with the reply it got), and a last ``end`` line
once the episode's record is in ``episodes.jsonl``. After a server restart the journals that
have no ``end`` line are the episodes in flight: a human navigator's episode is replayed and
resumed; an agent's is replayed and recorded as abandoned. Lines are flushed as they are
written (a killed process loses none); the settings and the end are also fsynced. A torn last
line (a kill mid-write) is ignored when reading.

Session codes are credentials, so the journal keeps only their SHA-256 digests.
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import IO, Any

from vlln.errors import DataFormatError
from vlln.files import ReadCap, parse_json, writing
from vlln.tasks.oracle_protocol import QuestionType, Reply

JOURNAL_FOLDER = "sessions"
# One session is a few hundred lines of tens of bytes each.
JOURNAL_CAP = ReadCap("a session journal", 16)


def code_digest(code: str) -> str:
    return hashlib.sha256(code.encode("utf-8")).hexdigest()


@dataclass(frozen=True)
class SessionSpec:
    """Who plays which episode with which oracle; the journal's first line."""

    session_id: str
    episode_index: int
    episode_id: str
    scene_id: str
    navigator: str  # "human:<participant>" or an agent name
    oracle: str  # an OracleKind value
    budget: int
    seed: int
    navigator_code: str | None = None  # SHA-256 digests of the codes
    oracle_code: str | None = None

    @property
    def human_navigator(self) -> bool:
        return self.navigator.startswith("human:")


@dataclass(frozen=True)
class Step:
    """One journaled navigator output: an action name, a question with its reply (None when
    refused), or an output that was not an action."""

    action: str | None = None
    question: str | None = None
    reply: Reply | None = None
    invalid: str | None = None


@dataclass(frozen=True)
class JournalContents:
    spec: SessionSpec
    steps: list[Step]
    ended: bool


class Journal:
    """Appends one session's lines (module doc)."""

    def __init__(self, folder: Path, spec: SessionSpec) -> None:
        self.path = folder / f"{spec.session_id}.jsonl"
        with writing(self.path):
            folder.mkdir(parents=True, exist_ok=True)
            fresh = not self.path.exists()
            if not fresh:
                _cut_torn_line(self.path)
            self._handle: IO[bytes] = self.path.open("ab")
        if fresh:
            self._write({"kind": "session", **asdict(spec)}, durable=True)

    def action(self, name: str) -> None:
        self._write({"kind": "action", "action": name})

    def talk(self, question: str, reply: Reply | None) -> None:
        data = None if reply is None else {**asdict(reply), "question_type": reply.question_type}
        self._write({"kind": "talk", "question": question, "reply": data})

    def invalid(self, text: str) -> None:
        self._write({"kind": "invalid", "text": text})

    def end(self, outcome: str) -> None:
        self._write({"kind": "end", "outcome": outcome}, durable=True)

    def close(self) -> None:
        self._handle.close()

    def _write(self, data: dict[str, Any], durable: bool = False) -> None:
        with writing(self.path):
            self._handle.write((json.dumps(data, separators=(",", ":")) + "\n").encode("utf-8"))
            self._handle.flush()
            if durable:
                os.fsync(self._handle.fileno())


def _cut_torn_line(path: Path) -> None:
    """Cut a partial last line (a kill mid-write), so the next line starts on its own."""
    data = JOURNAL_CAP.read(path)
    complete = data.rfind(b"\n") + 1
    if complete < len(data):
        with path.open("r+b") as handle:
            handle.truncate(complete)
            os.fsync(handle.fileno())


def read_journal(path: Path) -> JournalContents:
    """A journal's settings, steps and whether it ended; a torn last line is ignored, and
    any other damage (:func:`~vlln.files.parse_json`'s included) is one line naming it."""
    data = JOURNAL_CAP.read(path)
    lines = data[: data.rfind(b"\n") + 1].split(b"\n")[:-1]
    if not lines:
        raise DataFormatError(f"{path} holds no session settings; delete it")
    try:
        entries = [parse_json(line) for line in lines]
        header = dict(entries[0])
        if header.pop("kind") != "session":
            raise KeyError("kind")
        spec = SessionSpec(**header)
        steps = [_step(entry) for entry in entries[1:] if entry["kind"] != "end"]
    except (KeyError, TypeError, ValueError) as error:
        raise DataFormatError(f"{path} is not a session journal ({error}); move it away") from None
    return JournalContents(spec, steps, entries[-1]["kind"] == "end")


def _step(entry: dict[str, Any]) -> Step:
    kind = entry["kind"]
    if kind == "action":
        return Step(action=str(entry["action"]))
    if kind == "invalid":
        return Step(invalid=str(entry["text"]))
    if kind == "talk":
        reply = entry["reply"]
        if reply is not None:
            reply = Reply(**{**reply, "question_type": QuestionType(reply["question_type"])})
        return Step(question=str(entry["question"]), reply=reply)
    raise KeyError(f"kind {kind!r}")


def unfinished_journals(out: Path) -> list[JournalContents]:
    """The journals under ``out`` without an end line, oldest first."""
    folder = out / JOURNAL_FOLDER
    if not folder.is_dir():
        return []
    paths = sorted(folder.glob("*.jsonl"), key=lambda p: (p.stat().st_mtime, p.name))
    return [contents for contents in map(read_journal, paths) if not contents.ended]
