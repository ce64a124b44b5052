"""The record of one finished episode: everything the metrics need, nothing kept only in memory.

The evaluation runner writes one :class:`EpisodeRecord` per line (JSON); ``vlln score``
recomputes every metric from these lines alone, so a record stores raw inputs (the geodesic
distance to the goal's view points after every step, what the agent stopped in front of, when
the target was first seen) rather than verdicts.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from enum import StrEnum
from typing import Any

from vlln.errors import DataFormatError
from vlln.tasks.record_check import check_object


class EndReason(StrEnum):
    """Why an episode ended."""

    STOP = "stop"  # the agent chose STOP
    STEP_CAP = "step_cap"  # 500 counted steps (STOP/FORWARD/TURN)
    LOOK_CAP = "look_cap"  # too many LOOK actions
    TALK_CAP = "talk_cap"  # too many TALK actions
    ERROR = "error"  # the agent raised or kept returning garbage


class StopReason(StrEnum):
    """Why an agent chose STOP, as it reports it (see vlln.agents.protocol.ReportsStopReason)."""

    CANDIDATE = "candidate"  # at the object it took for the target
    EXPLORED = "explored"  # nothing left to explore and nothing it took for the target


@dataclass(frozen=True)
class DialogTurn:
    """One question and its answer; ``step`` is the counted step at which it was asked."""

    step: int
    question: str
    answer: str
    question_type: str  # attribute | route | disambiguation | other | refused
    answered: bool  # False once the dialog budget is spent
    # How the oracle answered (records written before these fields read as the rule oracle):
    backend: str = "rules"  # "rules", "offline", "openai:<model>@<host>"; "none" when refused
    latency_ms: float = 0.0  # time the oracle's language model took
    prompt_tokens: int = 0
    completion_tokens: int = 0
    fallback: bool = False  # offline logic stood in for a failed model call
    # The run does not allow questions of this type: answered with the refusal, turn spent
    # (written only when true).
    type_refused: bool = False
    # The kind of help a helpful oracle gave (vlln.oracle.helpful); written only when set.
    help_kind: str = ""


MAX_STORED_OUTPUT_CHARS = 2048  # of a model's raw output, per call


@dataclass(frozen=True)
class ModelCall:
    """One call of a model agent's model: its raw output (or why there is none) and cost.

    The output is stored up to :data:`MAX_STORED_OUTPUT_CHARS` (a valid one is a few hundred
    characters); what a server that ignores ``max_tokens`` sent beyond that is cut, and
    ``truncated_chars`` says how much, so run health can count it."""

    step: int  # counted steps taken before the call
    text: str | None  # the raw output (its first MAX_STORED_OUTPUT_CHARS), None when it failed
    error: str | None = None  # why the server gave no output
    look_down: bool = False  # the call showed the look-down image (a pixel goal may follow)
    latency_ms: float = 0.0
    prompt_tokens: int = 0
    completion_tokens: int = 0
    truncated_chars: int = 0  # characters of the output cut before storing
    prompt_digest: str = ""  # vlln.prompt.prompt_digest of the prompt, where the agent built it


@dataclass(frozen=True)
class EpisodeRecord:
    """One finished episode of one agent on one task with one dialog budget."""

    episode_id: str
    scene_id: str
    task: str  # iign | ign | objectnav
    agent: str
    budget: int  # questions the oracle answers
    object_category: str
    target_ids: list[int]  # goal instances (one for IIGN/IGN, all of the category for ObjectNav)
    end_reason: str  # an EndReason value
    steps: int  # counted steps
    geodesic_start: float  # d0: start to the nearest goal view point, metres
    geodesic_trace: list[float]  # after every counted step, metres (inf: unreachable)
    path_length: float  # L: sum of straight-line displacements
    stop_instance_id: int | None  # what it stopped at (see vlln.tasks.stop)
    stop_instance_category: str | None
    target_seen_step: int | None  # first step the target was observed (see metrics)
    positions: list[list[float]] = field(default_factory=list)  # [x, z, yaw] per step
    # Height y of every position, in houses with several storeys only (where (x, z) can be
    # two places); absent from the JSON of a one-storey house's record.
    heights: list[float] = field(default_factory=list)
    actions: list[str] = field(default_factory=list)
    dialog: list[DialogTurn] = field(default_factory=list)
    failed_actions: int = 0  # unparseable or invalid agent outputs
    error: str | None = None
    # Failed actions by kind ("parse", "server", "goal", "invalid"); records written before
    # this field read as empty.
    failures: dict[str, int] = field(default_factory=dict)
    model_calls: list[ModelCall] = field(default_factory=list)  # model agents only
    detector: str | None = None  # the agent's object detector ("truth", "noisy"); None: none
    oracle: str | None = None  # rules | llm | human; None: not stated (vlln eval: the rule oracle)
    # Stopped episodes only; absent from the JSON when None (and in records written before):
    stop_reason: str | None = None  # a StopReason value, when the agent reported one
    # Geodesic metres from the stop to the nearest view point of a same-category instance
    # that is not a goal; None: no such instance is reachable (always on ObjectNav).
    distractor_distance: float | None = None

    @property
    def agent_label(self) -> str:
        """The agent as tables name it, with its detector: "frontier (noisy detector)"."""
        return agent_label(self.agent, self.detector)

    @property
    def stopped(self) -> bool:
        return self.end_reason == EndReason.STOP

    @property
    def geodesic_final(self) -> float:
        return self.geodesic_trace[-1] if self.geodesic_trace else self.geodesic_start

    def to_json(self) -> dict[str, Any]:
        data = asdict(self)
        data["geodesic_trace"] = [_finite_or_none(d) for d in self.geodesic_trace]
        data["geodesic_start"] = _finite_or_none(self.geodesic_start)
        if not self.heights:
            del data["heights"]
        for name in _OMITTED_WHEN_NONE:
            if data[name] is None:
                del data[name]
        for turn in data["dialog"]:
            for name in ("type_refused", "help_kind"):  # written only when set
                if not turn[name]:
                    del turn[name]
        for call in data["model_calls"]:  # written only when something was cut or built
            for name in ("truncated_chars", "prompt_digest"):
                if not call[name]:
                    del call[name]
        return data

    @staticmethod
    def from_json(data: dict[str, Any]) -> EpisodeRecord:
        """Build a record from its JSON object, every field checked for type and range first
        (:mod:`vlln.tasks.record_check`) and every counter against the steps it counts (see
        :func:`_check_counts`); a bad one raises :class:`DataFormatError` naming it."""
        check_object(
            EpisodeRecord,
            data,
            signed=("positions", "heights"),
            non_empty=_IDENTITY_FIELDS,
            nullable=("geodesic_start", "geodesic_trace"),
        )
        if data["end_reason"] not in _END_REASONS:
            raise DataFormatError(
                f"field 'end_reason' must be one of {', '.join(_END_REASONS)}, "
                f"got {data['end_reason']!r:.60}"
            )
        if data.get("stop_reason") is not None and data["stop_reason"] not in _STOP_REASONS:
            raise DataFormatError(
                f"field 'stop_reason' must be one of {', '.join(_STOP_REASONS)}, "
                f"got {data['stop_reason']!r:.60}"
            )
        for index, position in enumerate(data.get("positions", [])):
            if len(position) != 3:
                raise DataFormatError(f"field 'positions[{index}]' must be [x, z, yaw]")
        heights = data.get("heights", [])
        if heights and len(heights) != len(data.get("positions", [])):
            raise DataFormatError(
                f"field 'heights' has {len(heights)} values for "
                f"{len(data.get('positions', []))} positions; give one height per position"
            )
        _check_counts(data)
        values = dict(data)
        values["dialog"] = [DialogTurn(**turn) for turn in values.get("dialog", [])]
        values["model_calls"] = [ModelCall(**call) for call in values.get("model_calls", [])]
        values["geodesic_trace"] = [_none_to_inf(d) for d in values["geodesic_trace"]]
        values["geodesic_start"] = _none_to_inf(values["geodesic_start"])
        return EpisodeRecord(**values)


def _check_counts(data: dict[str, Any]) -> None:
    """Tie the counters to the trace, as the environment writes them: one distance per counted
    step, a failed action is a counted step, the failures by kind add up to the failed
    actions, and nothing happens after the last step. A line that breaks one was edited or
    forged, and its numbers would reach the metrics unbounded."""
    steps = data["steps"]
    trace = len(data["geodesic_trace"])
    if steps != trace:
        raise DataFormatError(
            f"field 'steps' is {steps} but 'geodesic_trace' holds {trace} distances; "
            "a record has one distance per counted step"
        )
    failed = data.get("failed_actions", 0)
    if failed > steps:
        raise DataFormatError(
            f"field 'failed_actions' is {failed}, more than the {steps} counted steps; "
            "every failed action is a counted step"
        )
    by_kind = data.get("failures", {})
    if by_kind and sum(by_kind.values()) != failed:
        raise DataFormatError(
            f"field 'failures' counts {sum(by_kind.values())} failed actions by kind but "
            f"'failed_actions' is {failed}; the kinds add up to the total"
        )
    positions = len(data.get("positions", []))
    if positions > steps + 1:
        raise DataFormatError(
            f"field 'positions' holds {positions} positions for {steps} counted steps; "
            "a record has the start and one position per move"
        )
    seen = data["target_seen_step"]
    if seen is not None and seen > steps:
        raise DataFormatError(
            f"field 'target_seen_step' is {seen}, after the last of {steps} counted steps"
        )
    for name in ("dialog", "model_calls"):
        for index, item in enumerate(data.get(name, [])):
            if item["step"] > steps:
                raise DataFormatError(
                    f"field '{name}[{index}].step' is {item['step']}, after the last of "
                    f"{steps} counted steps"
                )
    answered = sum(1 for turn in data.get("dialog", []) if turn["answered"])
    if answered > data["budget"]:
        raise DataFormatError(
            f"field 'dialog' holds {answered} answered questions, more than the budget of "
            f"{data['budget']}"
        )


_IDENTITY_FIELDS = ("episode_id", "scene_id", "task", "agent", "object_category")
_END_REASONS = tuple(reason.value for reason in EndReason)
_STOP_REASONS = tuple(reason.value for reason in StopReason)
_OMITTED_WHEN_NONE = ("stop_reason", "distractor_distance")


def agent_label(agent: str, detector: str | None) -> str:
    """An agent's name with the detector it perceived through, when it has one."""
    return agent if detector is None else f"{agent} ({detector} detector)"


def _finite_or_none(value: float) -> float | None:
    """JSON has no infinity; an unreachable distance is written as null. Finite distances keep
    every digit: rounding could carry a stop at 0.24999 m over the 0.25 m success radius."""
    return None if value == float("inf") else value


def _none_to_inf(value: float | None) -> float:
    return float("inf") if value is None else float(value)
