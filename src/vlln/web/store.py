"""The sessions of one server and the output folder they write to.

The folder is an ordinary results folder (``episodes.jsonl``, read by ``vlln score`` and
``vlln report``) plus ``web.json`` (what the server serves; a restart must serve the same) and
the session journals (:mod:`vlln.web.journal`). The store holds the folder's lock for its
whole life, so two servers (or a server and ``vlln eval``) never write into one folder.

Codes: a session has one unguessable code per human role (:func:`secrets.token_urlsafe`,
96 bits), and a code opens only its own role's page, so the navigator's code never shows the
oracle's privileged view. Only the codes' digests are kept, on disk and in memory.
"""

from __future__ import annotations

import json
import secrets
import threading
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from vlln.errors import ConfigError, DataFormatError
from vlln.eval.results import RecordKey, RecordWriter, RunDirectory, record_key
from vlln.eval.run_dir import episodes_file
from vlln.files import (
    ReadCap,
    check_output_folder,
    parse_json,
    refuse_other_settings,
    write_text_atomic,
)
from vlln.tasks.episode import Episode
from vlln.tasks.record import EpisodeRecord
from vlln.web.changes import ChangeSignal
from vlln.web.config import (
    HUMAN_PREFIX,
    OracleKind,
    WebConfig,
    check_participant,
    navigator_label,
)
from vlln.web.journal import (
    JOURNAL_FOLDER,
    Journal,
    SessionSpec,
    Step,
    code_digest,
    unfinished_journals,
)
from vlln.web.session import EpisodeSession, OracleFactory, Status

SETTINGS_FILE = "web.json"
KEPT_FINISHED = 64  # finished sessions kept for their pages to show the outcome
RESTARTED = "the server stopped during the episode"
NAVIGATOR = "navigator"
ORACLE = "oracle"


@dataclass(frozen=True)
class Created:
    """A new session and the codes its people need (None for a role played by software)."""

    session_id: str
    episode_index: int
    navigator_code: str | None
    oracle_code: str | None


class SessionStore:
    """Live and finished sessions, their codes, and the record writer (module doc)."""

    def __init__(
        self, config: WebConfig, make_oracle: OracleFactory, source: str, loop: Any = None
    ) -> None:
        self.config = config
        self.source = source
        self._make_oracle = make_oracle
        self._loop = loop
        self._lock = threading.Lock()
        self._sessions: dict[str, EpisodeSession] = {}
        self._codes: dict[str, tuple[str, str]] = {}  # digest -> (session id, role)
        self._exit = ExitStack()
        self._writer: RecordWriter | None = None

    # ------------------------------------------------------------ life cycle
    def open(self) -> None:
        """Take the folder, check its settings, and resume or record the episodes in flight."""
        out = self.config.out
        check_output_folder(out)
        out.mkdir(parents=True, exist_ok=True)
        self._check_settings()
        self._writer = self._exit.enter_context(RunDirectory(out).writing())
        finished = {record_key(record) for record in self._writer.records}
        for contents in unfinished_journals(out):
            spec = contents.spec
            episode = self._episode(spec)
            if self._key(spec.navigator, OracleKind(spec.oracle), spec.episode_index) in finished:
                Journal(out / JOURNAL_FOLDER, spec).end(Status.FINISHED)
                continue
            resume = spec.human_navigator
            session = self._session(
                spec, episode, contents.steps, None if resume else f"abandoned: {RESTARTED}"
            )
            self._register(session)
            session.start()

    def attach(self, loop: Any) -> None:
        """Let pages waiting on ``loop`` (the server's) hear of every session's changes."""
        with self._lock:
            self._loop = loop
            for session in self._sessions.values():
                session.signal.attach(loop)

    def close(self) -> None:
        """Stop every live session (their journals keep them for the next start)."""
        with self._lock:
            live = [s for s in self._sessions.values() if not s.done]
        for session in live:
            session.stop()
        self._exit.close()

    # ------------------------------------------------------------ sessions
    def create(self, navigator: str, oracle: OracleKind, episode_index: int | None) -> Created:
        """Start a session; ``navigator`` is ``human:<participant>`` or an agent name."""
        if navigator.startswith(f"{HUMAN_PREFIX}:"):
            check_participant(navigator.split(":", 1)[1])
        elif navigator not in self.config.agents:
            raise ConfigError(
                f"unknown navigator {navigator[:40]!r}; a person (human:<name>) or one of: "
                + ", ".join(self.config.agents)
            )
        if oracle not in self.config.oracles:
            raise ConfigError(
                f"oracle {oracle.value!r} is not offered here; choose one of: "
                + ", ".join(kind.value for kind in self.config.oracles)
            )
        human_navigator = navigator.startswith(f"{HUMAN_PREFIX}:")
        if not human_navigator and oracle != OracleKind.HUMAN:
            raise ConfigError("an agent with a software oracle needs no browser: use vlln eval")
        with self._lock:
            live = sum(1 for s in self._sessions.values() if not s.done)
            if live >= self.config.max_live_sessions:
                raise ConfigError(
                    f"{live} sessions are already being played (the limit is "
                    f"{self.config.max_live_sessions}); finish one first"
                )
            index = self._choose_episode(navigator, oracle, episode_index)
            episode = self.config.episodes[index]
            navigator_code = secrets.token_urlsafe(12) if human_navigator else None
            oracle_code = secrets.token_urlsafe(12) if oracle == OracleKind.HUMAN else None
            spec = SessionSpec(
                session_id=secrets.token_hex(8),
                episode_index=index,
                episode_id=episode.episode_id,
                scene_id=episode.scene_id,
                navigator=navigator,
                oracle=oracle.value,
                budget=self.config.dialog_budget,
                seed=self.config.seed,
                navigator_code=None if navigator_code is None else code_digest(navigator_code),
                oracle_code=None if oracle_code is None else code_digest(oracle_code),
            )
            session = self._session(spec, episode)
            self._register(session)
            self._forget_old_sessions()
        session.start()
        return Created(spec.session_id, index, navigator_code, oracle_code)

    def find(self, code: str) -> tuple[EpisodeSession, str] | None:
        """The session a code opens and the role it opens it as; None for an unknown code."""
        found = self._codes.get(code_digest(code))
        if found is None:
            return None
        session = self._sessions.get(found[0])
        return None if session is None else (session, found[1])

    def overview(self) -> dict[str, Any]:
        """Counts for the lobby: sessions live, finished and abandoned, records written."""
        with self._lock:
            statuses = [s.view.status for s in self._sessions.values()]
            records = len(self._writer.records) if self._writer else 0
        return {
            "live": sum(1 for s in statuses if s not in (Status.FINISHED, Status.ABANDONED)),
            "finished": statuses.count(Status.FINISHED),
            "abandoned": statuses.count(Status.ABANDONED),
            "records": records,
        }

    def records(self) -> list[EpisodeRecord]:
        with self._lock:
            return list(self._writer.records) if self._writer else []

    # ------------------------------------------------------------ internals
    def _finish(self, session: EpisodeSession, record: EpisodeRecord) -> None:
        with self._lock:
            if self._writer is None:
                raise ConfigError("the session store is closed")
            if record_key(record) in {record_key(r) for r in self._writer.records}:
                return  # already recorded before a restart: never count an episode twice
            self._writer.append(record)

    def _choose_episode(self, navigator: str, oracle: OracleKind, wanted: int | None) -> int:
        episodes = self.config.episodes
        taken = self._taken_keys()
        if wanted is not None:
            if not 0 <= wanted < len(episodes):
                raise ConfigError(f"episode {wanted} is outside 0..{len(episodes) - 1}")
            if self._key(navigator, oracle, wanted) in taken:
                raise ConfigError(
                    f"{navigator} has played or is playing episode {wanted} with this oracle; "
                    "choose another episode or another participant name"
                )
            return wanted
        for index in range(len(episodes)):
            if self._key(navigator, oracle, index) not in taken:
                return index
        raise ConfigError(f"{navigator} has played every episode served here with this oracle")

    def _taken_keys(self) -> set[RecordKey]:
        keys = {record_key(record) for record in (self._writer.records if self._writer else [])}
        return keys | {s.key for s in self._sessions.values() if not s.done}

    def _key(self, navigator: str, oracle: OracleKind, index: int) -> RecordKey:
        episode = self.config.episodes[index]
        label = navigator_label(navigator, oracle)
        task, budget = self.config.task.value, self.config.dialog_budget
        return (label, task, budget, episode.scene_id, episode.episode_id)

    def _session(
        self,
        spec: SessionSpec,
        episode: Episode,
        replay: list[Step] | None = None,
        abandon_after_replay: str | None = None,
    ) -> EpisodeSession:
        return EpisodeSession(
            spec,
            episode,
            self.config,
            Journal(self.config.out / JOURNAL_FOLDER, spec),
            self._make_oracle,
            self._finish,
            ChangeSignal(self._loop),
            replay,
            abandon_after_replay,
        )

    def _register(self, session: EpisodeSession) -> None:
        spec = session.spec
        self._sessions[spec.session_id] = session
        for digest, role in ((spec.navigator_code, NAVIGATOR), (spec.oracle_code, ORACLE)):
            if digest is not None:
                self._codes[digest] = (spec.session_id, role)

    def _forget_old_sessions(self) -> None:
        """Drop the oldest finished sessions beyond :data:`KEPT_FINISHED`, with their codes,
        so memory stays bounded however long the server runs (their records are on disk)."""
        finished = [s for s in self._sessions.values() if s.done]
        for session in finished[: max(0, len(finished) - KEPT_FINISHED)]:
            del self._sessions[session.spec.session_id]
        known = set(self._sessions)
        self._codes = {k: v for k, v in self._codes.items() if v[0] in known}

    def _episode(self, spec: SessionSpec) -> Episode:
        episodes = self.config.episodes
        index = spec.episode_index
        if not 0 <= index < len(episodes) or episodes[index].episode_id != spec.episode_id:
            raise ConfigError(
                f"session {spec.session_id} played episode {spec.episode_id} "
                f"({spec.scene_id}), which the served episodes lack; serve the same episodes "
                "to resume it"
            )
        return episodes[index]

    def _check_settings(self) -> None:
        config = self.config
        wanted = {
            "source": self.source,
            "episodes": len(config.episodes),
            "task": config.task.value,
            "dialog_budget": config.dialog_budget,
            "max_steps": config.max_steps,
            "seed": config.seed,
        }
        path = config.out / SETTINGS_FILE
        if path.exists():
            refuse_other_settings(config.out, _stored_settings(path), wanted, "a study")
        elif episodes_file(config.out).exists():
            raise ConfigError(
                f"{config.out} holds episode records from another command; use another --out"
            )
        else:
            write_text_atomic(path, json.dumps(wanted, indent=2) + "\n")


# web.json holds a study's settings: well under a kB.
_SETTINGS_CAP = ReadCap("a web.json", 1)


def _stored_settings(path: Path) -> dict[str, Any]:
    """``web.json`` as stored; a damaged one is one line (the study's records stay readable
    by ``vlln score`` and ``vlln report``, whatever this file holds)."""
    try:
        stored = parse_json(_SETTINGS_CAP.read(path))
        if not isinstance(stored, dict):
            raise DataFormatError(f"a JSON {type(stored).__name__}, not an object")
    except DataFormatError as error:
        raise DataFormatError(
            f"{path} is damaged ({error}); restore the study's settings, or serve into "
            "another --out"
        ) from None
    return stored
