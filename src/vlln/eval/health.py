"""Run health: whether a run is complete, which lines were skipped and which turns failed.

A benchmark number must never come from a partial or degraded run without saying so. Every
command that reads a run (``vlln eval``, ``vlln score``, ``vlln report``) states the health
in one line and in what it writes. Failures are counted per kind in :data:`FAILURE_KINDS`, a
mapping of name to a per-record counter; a new kind of failure (a model server's errors, an
agent's unparseable outputs) is one more entry there. Refused episodes (unplayable in their
scene, :mod:`vlln.eval.refusals`) have no record: they are counted apart, named, and make a
run complete without being scored.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from vlln.eval.refusals import Refusal
from vlln.eval.results import RunContents
from vlln.tasks.record import EndReason, EpisodeRecord

FailureCounter = Callable[[EpisodeRecord], int]

FAILURE_KINDS: dict[str, FailureCounter] = {
    "oracle fallback turns": lambda record: sum(turn.fallback for turn in record.dialog),
    "agent errors": lambda record: int(record.end_reason == EndReason.ERROR),
    "failed actions": lambda record: record.failed_actions,
    "unreadable model replies": lambda record: record.failures.get("parse", 0),
    "model server failures": lambda record: record.failures.get("server", 0),
    "truncated model outputs": lambda record: sum(
        call.truncated_chars > 0 for call in record.model_calls
    ),
}
"""Failure kind -> how many times one episode record shows it."""

_EXAMPLES = 3  # skipped lines named in the one-line statement
_NOT_A_MODEL = ("rules", "helpful", "offline", "none")  # dialog-turn backends that never fall back


@dataclass(frozen=True)
class RunHealth:
    """What a set of records is worth: complete or not, lines skipped, failures by kind."""

    finished: int  # valid episode lines
    planned: int | None  # episode lines the run(s) planned; None when run.json does not say
    skipped: dict[str, int]  # lines not counted, by kind (invalid, duplicate, torn, set aside)
    failures: dict[str, int]  # FAILURE_KINDS name -> count, every kind present
    backends: list[str]  # oracle backends that answered turns
    examples: list[str]  # the first skipped lines, described (file:line: reason)
    refused: int = 0  # planned episode lines refused as unplayable in their scene
    refused_episodes: list[str] = field(default_factory=list)  # "<episode> (<scene>): reason"
    missing_shards: tuple[str, ...] = ()  # shards ("i/n") of the run(s) that were not read
    # Questions answered with the refusal because the run does not allow their type
    # (--question-types): by design, not a failure, but every reader should see it.
    refused_questions: int = 0
    model_calls: int = 0  # calls of a model agent's model
    model_turns: int = 0  # dialog turns a language-model oracle was asked to answer

    @property
    def complete(self) -> bool:
        """Every planned line is there or refused (only planned lines count as finished), and
        no shard of the run is missing."""
        return (
            self.planned is not None
            and self.finished + self.refused >= self.planned
            and not self.missing_shards
        )

    @property
    def clean(self) -> bool:
        """Complete, nothing skipped or refused, no failure of any kind."""
        return (
            self.complete
            and not self.skipped
            and not self.refused
            and not any(self.failures.values())
        )

    @property
    def unmeasured(self) -> list[str]:
        """What never answered in the whole run, so that its numbers measure a server's
        failures (a model that gave no readable reply, an oracle answered by fallbacks alone)
        and not the agent: each is said in words, as a reason the run is no result."""
        found = []
        failed_calls = self.failures["unreadable model replies"]
        failed_calls += self.failures["model server failures"]
        if self.model_calls and failed_calls >= self.model_calls:
            found.append(f"none of {self.model_calls} model calls gave a readable reply")
        if self.oracle_silent:
            found.append(self.oracle_silent)
        return found

    @property
    def servers_silent(self) -> str:
        """Why the run's numbers measure its servers and not the agent ("" when they do not):
        no model call got a reply from its server, or the oracle's model answered nothing.
        ``vlln eval`` and ``vlln score`` exit with status 1 on it."""
        if self.model_calls and self.failures["model server failures"] >= self.model_calls:
            return f"none of {self.model_calls} model calls got a reply from the model's server"
        return self.oracle_silent

    @property
    def oracle_silent(self) -> str:
        """Why the oracle's model answered no question of the run ("" when it answered one)."""
        if self.model_turns and self.failures["oracle fallback turns"] >= self.model_turns:
            return (
                f"the oracle's model answered none of {self.model_turns} questions (every "
                "answer a rule fallback)"
            )
        return ""

    def line(self) -> str:
        """The health in one line, e.g. ``run health: INCOMPLETE, 11 of 12 episode lines;
        skipped lines: torn 1 (runs/f/episodes.jsonl:12: ...); failures: none``."""
        if self.planned is None:
            state = f"{self.finished} episode lines (planned count unknown)"
        elif self.complete:
            state = f"complete, {self.finished} of {self.planned} episode lines"
        else:
            state = f"INCOMPLETE, {self.finished} of {self.planned} episode lines"
        if self.refused:
            state += f" and {self.refused} refused"
        if self.missing_shards:
            state += f" (shards {', '.join(self.missing_shards)} not given)"
        parts = [f"run health: {state}"]
        if self.unmeasured:
            parts.append("NOTHING MEASURED: " + ", and ".join(self.unmeasured))
        if self.refused:
            named = "; ".join(self.refused_episodes[:_EXAMPLES])
            more = len(self.refused_episodes) - _EXAMPLES
            named += f"; {more} more" if more > 0 else ""
            parts.append(f"refused episodes {len(self.refused_episodes)} ({named})")
        if self.refused_questions:
            parts.append(f"questions refused for their type {self.refused_questions}")
        if self.skipped:
            counts = ", ".join(f"{kind} {count}" for kind, count in self.skipped.items())
            where = f" ({'; '.join(self.examples)})" if self.examples else ""
            parts.append(f"skipped lines: {counts}{where}")
        else:
            parts.append("no skipped lines")
        failed = {kind: count for kind, count in self.failures.items() if count}
        if failed:
            parts.append("failures: " + ", ".join(f"{kind} {n}" for kind, n in failed.items()))
        else:
            parts.append("no failed or fallback turns")
        return "; ".join(parts)

    def to_json(self) -> dict[str, Any]:
        return {
            "complete": self.complete,
            "finished": self.finished,
            "planned": self.planned,
            "missing_shards": list(self.missing_shards),
            "skipped_lines": dict(self.skipped),
            "failures": dict(self.failures),
            "oracle_backends": list(self.backends),
            "refused_lines": self.refused,
            "refused_episodes": list(self.refused_episodes),
            "refused_questions": self.refused_questions,
            "unmeasured": self.unmeasured,
        }


def run_health(contents: RunContents) -> RunHealth:
    """The health of what :func:`vlln.eval.results.load_runs` read."""
    return health_of(
        contents.records,
        contents.planned,
        contents.skipped_kinds(),
        contents.refused,
        contents.missing_shards,
    )


def health_of(
    records: Sequence[EpisodeRecord],
    planned: int | None,
    skipped: Sequence[tuple[str, str]] = (),
    refused: Sequence[Refusal] = (),
    missing_shards: Sequence[str] = (),
) -> RunHealth:
    """Health of ``records``; ``skipped`` holds (kind, description) per line not counted,
    ``refused`` the refusals of the run."""
    skipped_counts: dict[str, int] = {}
    for kind, _ in skipped:
        skipped_counts[kind] = skipped_counts.get(kind, 0) + 1
    failures = {
        kind: sum(count(record) for record in records) for kind, count in FAILURE_KINDS.items()
    }
    backends = sorted({turn.backend for record in records for turn in record.dialog})
    return RunHealth(
        finished=len(records),
        planned=planned,
        skipped=skipped_counts,
        failures=failures,
        backends=[backend for backend in backends if backend != "none"],
        examples=[text for _, text in skipped if text][:_EXAMPLES],
        refused=len(refused),
        refused_episodes=list(dict.fromkeys(refusal.describe() for refusal in refused)),
        missing_shards=tuple(missing_shards),
        refused_questions=sum(turn.type_refused for record in records for turn in record.dialog),
        model_calls=sum(len(record.model_calls) for record in records),
        model_turns=sum(
            turn.backend not in _NOT_A_MODEL for record in records for turn in record.dialog
        ),
    )
