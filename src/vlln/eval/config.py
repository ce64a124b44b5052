"""What an evaluation run is: the arguments that decide its episode lines.

A run directory stores these as ``run.json``; a restart with other arguments would mix two
different experiments in one results file, so the runner names what changed and refuses
(:func:`vlln.files.refuse_other_settings`). Settings that do not change a single episode line
(where built splits are cached, whether a progress bar is shown, how many episodes one
invocation plays) are not part of the run.
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Self

from pydantic import (
    AfterValidator,
    BeforeValidator,
    Field,
    PlainSerializer,
    field_validator,
    model_validator,
)
from pydantic_settings import CLI_SUPPRESS, NoDecode

from vlln.agents.options import AgentOptions
from vlln.config import Config
from vlln.errors import ConfigError
from vlln.eval.run_dir import RUN_FACTS
from vlln.eval.sharding import Shard
from vlln.oracle.llm.openai_client import OpenAISettings
from vlln.oracle.rule_oracle import ALL_QUESTION_TYPES
from vlln.oracle.settings import (
    Disambiguation,
    OracleBackend,
    OracleSettings,
    parse_question_types,
)
from vlln.tasks.oracle_protocol import QuestionType
from vlln.tasks.spec import DEFAULT_MAX_STEPS, TaskType
from vlln.tasks.splits import (
    SPLIT_SIZES,
    SPLITS,
    TEST_PROTOCOL_EPISODES,
    TEST_PROTOCOL_SPLIT,
    source_split,
)
from vlln.world.generator.presets import DEFAULT_PRESET, SMALL, preset

DEFAULT_DIALOG_BUDGET = TaskType.IIGN.default_budget
"""Answered questions per IIGN episode (docs/reference-facts.md §1)."""


_BUDGET_RANGE = re.compile(r"^(\d+)-(\d+)$")

DEFAULT_MAX_FAILURES = 4
"""Failed requests in a row to the oracle's server that stop a run: four hanging requests
take about 2 minutes at the default 30 s deadline, where retrying every question for ever
would play the whole run on fallback answers."""

_ORACLE_FLAGS = {
    "oracle_model": "model",
    "oracle_base_url": "base_url",
    "oracle_api_key_env": "api_key_env",
    "oracle_timeout": "timeout_s",
    "oracle_retries": "max_retries",
    "oracle_max_failures": "max_failures",
}
"""The ``--oracle llm`` settings: EvalConfig field -> OpenAISettings field."""


def _budgets(value: Any) -> Any:
    """Budgets as given: ``"0-5"``, ``"0,5"``, ``"3"``, a number, or a list of those."""
    if isinstance(value, str):
        return parse_budgets(value)
    if isinstance(value, int):
        return (value,)
    if isinstance(value, list | tuple):
        parts = [_budgets(part) if isinstance(part, str | int) else (part,) for part in value]
        return tuple(budget for part in parts for budget in part)  # pydantic checks each
    return value


def _shard(value: Any) -> Shard:
    if isinstance(value, Shard):
        return value
    if not isinstance(value, str):
        raise ConfigError(f"cannot read shard {value!r}; write i/n, e.g. 0/4")
    return Shard.parse(value)


def _absolute(path: str | None) -> str | None:
    """A path as an absolute one, so that a run directory names the same file from anywhere."""
    return None if path is None else str(Path(path).expanduser().resolve())


def by_task(values: dict[str, Any]) -> tuple[int, ...]:  # named in --help
    """The default budgets of the (already checked) task: 5 on IIGN, 0 otherwise."""
    task = values.get("task")
    return default_budgets(task) if task else (DEFAULT_DIALOG_BUDGET,)


def _question_types(value: Any) -> Any:
    """Question types as given: ``"attribute,route"`` or a list of names."""
    if isinstance(value, list | tuple):
        value = ",".join(str(part) for part in value)
    if isinstance(value, str):
        return tuple(kind.value for kind in parse_question_types(value))
    return value


def _some_types(types: tuple[str, ...]) -> tuple[str, ...]:
    if not types:
        raise ConfigError(
            "give at least one question type (attribute, route, disambiguation, other); "
            "for no dialog at all use --budgets 0"
        )
    return types


# NoDecode: the command line's text reaches the validators as written ("0-5", "1/4").
Budgets = Annotated[tuple[int, ...], NoDecode, BeforeValidator(_budgets)]
ShardSetting = Annotated[Shard, NoDecode, PlainSerializer(str), BeforeValidator(_shard)]
AbsolutePath = Annotated[str | None, AfterValidator(_absolute)]
QuestionTypes = Annotated[
    tuple[str, ...],
    NoDecode,
    BeforeValidator(_question_types),
    AfterValidator(_some_types),
]


class EvalConfig(Config):
    """One evaluation run: which agent plays which episodes of which task, at which budgets.

    Episodes come either from a built-in ``split`` of procedural houses (its first ``houses``;
    by default one full cycle of the split: 61/15/14 houses for train/val/test, the paper's
    scene counts) or from a released-format ``episode_file``; exactly one is set.
    Fields are in ``run.json``'s key order.
    """

    file_keys: ClassVar[tuple[str, ...]] = RUN_FACTS

    agent: str
    """agent name (random, expert, frontier, frontier-compare, fbe, vlfm, openai-vlm, aiuta,
    vlln) or your own class as package.module:Class (docs/own-agent.md)"""
    task: str
    """iign, ign or objectnav"""
    split: str | None = "test"
    """built-in split: train, val, test or test500 (the paper's 500 test episodes)"""
    episode_file: AbsolutePath = None
    """released-format episode file (.json.gz), instead of a split"""
    episodes: int | None = None
    """first N episodes, after grouping by scene (none: all)"""
    budgets: Budgets = Field(default_factory=by_task)
    """dialog budgets, e.g. 0-5 or 0,5 (SR per budget, MSP); by default 5 on IIGN, else 0"""
    seed: int = 0
    """base seed of agents and oracle"""
    houses: int | None = None
    """houses of the split (none: all of it, 61/15/14)"""
    shard: ShardSetting = Shard(0, 1)
    """i/n: every episode whose index mod n is i"""
    max_steps: int = DEFAULT_MAX_STEPS
    """counted-step cap"""
    agent_options: Annotated[AgentOptions, CLI_SUPPRESS, PlainSerializer(AgentOptions.to_json)] = (
        AgentOptions()
    )
    """settings of agents that take them (openai-vlm: server, model, key variable, retries;
    vlln: model folder, device; frontier: dialog policy), never a secret; on the command line
    the model flags"""
    detector: str | None = None
    """object detector of agents that detect objects: truth (the frontier agent's default,
    privileged) or noisy; other agents take none"""
    preset: str = DEFAULT_PRESET
    """houses of a built-in split: mp3d (the benchmark's, calibrated to Matterport3D) or small
    (demo, fast tests)"""
    scenes: AbsolutePath = None
    """folder of scanned scenes (<scenes>/<scene>/) the episode file names"""
    oracle: Literal["rules", "llm", "helpful"] = "rules"
    """who answers questions: rules (offline), llm (the paper's language-model oracle over
    an OpenAI-compatible server; needs --oracle-model) or helpful (the rule oracle's answers
    and grounded help beyond them; offline, or worded by --oracle-model)"""
    oracle_model: str | None = None
    """--oracle llm or helpful: the served model's name, e.g. gpt-4o"""
    oracle_base_url: str | None = None
    """--oracle llm: the server, e.g. http://localhost:8000/v1 (none: OpenAI's)"""
    oracle_api_key_env: str | None = None
    """--oracle llm: the variable holding the API key, never stored (none: OPENAI_API_KEY)"""
    oracle_timeout: Annotated[float, Field(gt=0, allow_inf_nan=False)] | None = None
    """--oracle llm: deadline of each whole request in s (none: 30)"""
    oracle_retries: Annotated[int, Field(ge=0)] | None = None
    """--oracle llm: retries per request (none: 4)"""
    oracle_max_failures: Annotated[int, Field(ge=1)] | None = None
    """--oracle llm: failed requests in a row that stop the run (none: 4)"""
    question_types: QuestionTypes = tuple(kind.value for kind in ALL_QUESTION_TYPES)
    """question types the oracle answers, e.g. attribute,route (others get the refusal and
    cost their turn)"""
    disambiguation: Literal["plain", "cues"] = "plain"
    """answers to "is this the one?": plain (yes or no, the paper's) or cues (a no says how
    the target differs)"""

    @model_validator(mode="before")
    @classmethod
    def _defaults_from_others(cls, data: Any) -> Any:
        """An episode file replaces the default split; the agent options are checked against
        the agent's own options class (:data:`vlln.agents.registry.OPTIONS`)."""
        if not isinstance(data, dict):
            return data
        from vlln.agents.registry import agent_options

        data = dict(data)
        if data.get("episode_file") is not None and "split" not in data:
            data["split"] = None
        data["agent_options"] = agent_options(str(data.get("agent")), data.get("agent_options"))
        return data

    @field_validator("task")
    @classmethod
    def _task(cls, task: str) -> str:
        return TaskType.parse(task).value

    @model_validator(mode="after")
    def _check(self) -> Self:
        task = TaskType.parse(self.task)
        if (self.split is None) == (self.episode_file is None):
            raise ConfigError("give exactly one episode source: a split or an episode file")
        known = (*SPLITS, TEST_PROTOCOL_SPLIT)
        if self.split is not None and self.split not in known:
            raise ConfigError(f"unknown split {self.split!r}; choose one of: {', '.join(known)}")
        if self.split == TEST_PROTOCOL_SPLIT:
            episodes = TEST_PROTOCOL_EPISODES if self.episodes is None else self.episodes
            self._fill("episodes", episodes)
            if episodes > TEST_PROTOCOL_EPISODES or self.houses not in (None, 14):
                raise ConfigError(
                    f"split {TEST_PROTOCOL_SPLIT} is {TEST_PROTOCOL_EPISODES} episodes on the 14 "
                    "test houses; pass --episodes up to 500 and no --houses, or use --split test"
                )
        if self.episodes is not None and self.episodes < 1:
            raise ConfigError(f"--episodes must be at least 1, got {self.episodes}")
        if self.split is not None and self.houses is None:
            self._fill("houses", SPLIT_SIZES[source_split(self.split)])
        if self.episode_file is not None and self.houses is not None:
            raise ConfigError("--houses applies to built-in splits, not to an episode file")
        if self.houses is not None and self.houses < 1:
            raise ConfigError(f"--houses must be at least 1, got {self.houses}")
        if self.max_steps < 1:
            raise ConfigError(f"--max-steps must be at least 1, got {self.max_steps}")
        _check_budgets(self.budgets, task)
        from vlln.agents.registry import resolve_detector

        self._fill("detector", resolve_detector(self.agent, self.detector))
        preset(self.preset)
        self.oracle_settings()
        return self

    def oracle_settings(self) -> OracleSettings:
        """The run's oracle (:mod:`vlln.oracle.settings`); the llm flags need --oracle llm."""
        llm = None
        if self.oracle == OracleBackend.LLM.value and not self.oracle_model:
            raise ConfigError("--oracle llm needs --oracle-model, the served model's name")
        if self.oracle_model:
            llm = OpenAISettings(model=self.oracle_model, max_failures=DEFAULT_MAX_FAILURES)
            given = {
                setting: getattr(self, name)
                for name, setting in _ORACLE_FLAGS.items()
                if getattr(self, name) is not None
            }
            llm = dataclasses.replace(llm, **given)
        else:
            extra = [name for name in _ORACLE_FLAGS if getattr(self, name) is not None]
            if extra:
                flag = "--" + extra[0].replace("_", "-")
                raise ConfigError(
                    f"{flag} applies to a language model's oracle; add --oracle-model or drop it"
                )
        types = tuple(QuestionType(name) for name in self.question_types)
        backend, disambiguation = OracleBackend(self.oracle), Disambiguation(self.disambiguation)
        return OracleSettings(backend, llm, types, disambiguation)

    def _fill(self, name: str, value: Any) -> None:
        """Set a setting that its default leaves to the others (the model is frozen)."""
        object.__setattr__(self, name, value)

    @classmethod
    def from_json(cls, data: Any, where: str) -> Self:
        """Read a ``run.json``; files written before presets existed were played on the
        ``small`` houses, and before the disambiguation setting existed with cues."""
        if isinstance(data, dict):
            data = {"preset": SMALL.name, "disambiguation": Disambiguation.CUES.value, **data}
        return super().from_json(data, where)

    def run_settings(self) -> EvalConfig:
        """The settings of the run alone (a command's config also holds how to run it)."""
        if type(self) is EvalConfig:
            return self
        return EvalConfig(**{name: getattr(self, name) for name in EvalConfig.model_fields})


def _check_budgets(budgets: tuple[int, ...], task: TaskType) -> None:
    if not budgets:
        raise ConfigError("give at least one dialog budget")
    if len(set(budgets)) != len(budgets):
        raise ConfigError(f"dialog budgets repeat: {list(budgets)}")
    for budget in budgets:
        task.check_budget(budget)


def default_budgets(task: str) -> tuple[int, ...]:
    """IIGN runs with the reference's budget of 5, IGN and ObjectNav with 0 (IGN takes
    ``--budgets`` for dialog)."""
    return (TaskType.parse(task).default_budget,)


def parse_budgets(text: str) -> tuple[int, ...]:
    """``"0-5"`` -> (0, 1, 2, 3, 4, 5); ``"0,2,5"`` -> (0, 2, 5); ``"3"`` -> (3,)."""
    text = text.strip()
    match = _BUDGET_RANGE.match(text)
    if match is not None:
        low, high = int(match.group(1)), int(match.group(2))
        if high < low:
            raise ConfigError(f"budget range {text!r} runs backwards; write it low-high, e.g. 0-5")
        TaskType.IIGN.check_budget(high)  # before a range of 10**18 budgets is made
        return tuple(range(low, high + 1))
    try:
        return tuple(int(part) for part in text.split(","))
    except ValueError:
        raise ConfigError(
            f"cannot read dialog budgets {text!r}; write a range (0-5) or a list (0,2,5)"
        ) from None
