"""What an evaluation run is: the arguments that decide its episode lines.

A run directory stores these as ``run.json``; a restart with other arguments would mix two
different experiments in one results file, so :func:`describe_differences` names what changed
and the runner refuses. Settings that do not change a single episode line (where built splits
are cached, whether a progress bar is shown, how many episodes one invocation plays) are not
part of the run.
"""

from __future__ import annotations

import re
from dataclasses import asdict, dataclass, field
from typing import Any

from vlln.agents.registry import resolve_detector
from vlln.errors import ConfigError, DataFormatError
from vlln.eval.sharding import Shard
from vlln.tasks.spec import MAX_DIALOG_BUDGET, TaskType
from vlln.tasks.splits import SPLIT_SIZES, SPLITS
from vlln.tasks.test_protocol import TEST_PROTOCOL_EPISODES, TEST_PROTOCOL_SPLIT, source_split
from vlln.world.generator.presets import DEFAULT_PRESET, SMALL, preset

DEFAULT_DIALOG_BUDGET = TaskType.IIGN.default_budget
"""Answered questions per IIGN episode (docs/reference-facts.md §1)."""

_BUDGET_RANGE = re.compile(r"^(\d+)-(\d+)$")


@dataclass(frozen=True)
class EvalConfig:
    """One evaluation run: which agent plays which episodes of which task, at which budgets.

    Episodes come either from a built-in ``split`` of procedural houses (its first ``houses``;
    by default one full cycle of the split: 61/15/14 houses for train/val/test, the paper's
    scene counts) or from a released-format ``episode_file``; exactly one is set.
    ``episodes`` keeps the first N (all when ``None``) after grouping by scene.
    ``detector`` names the perception of agents that detect objects (the frontier agent's
    default is the ground-truth detector); other agents take none. ``scenes`` is the folder of
    scanned scenes the episodes name (``--scenes``), kept so that ``vlln video`` and ``vlln
    report`` find them again.
    """

    agent: str
    task: str
    split: str | None = "test"
    episode_file: str | None = None
    episodes: int | None = None
    budgets: tuple[int, ...] = (DEFAULT_DIALOG_BUDGET,)
    seed: int = 0
    houses: int | None = None
    shard: Shard = field(default_factory=lambda: Shard(0, 1))
    max_steps: int = 500
    # Settings of agents that take them (openai-vlm: server, model, key variable, retries);
    # never a secret. Run files written before this field read as no options.
    agent_options: dict[str, str] = field(default_factory=dict)
    detector: str | None = None
    # Houses of a built-in split: ``mp3d`` (the benchmark's) or ``small`` (demo, fast
    # tests). Run files written before presets existed read as ``small``, the houses they
    # were played on.
    preset: str = DEFAULT_PRESET
    scenes: str | None = None

    def __post_init__(self) -> None:
        task = TaskType.parse(self.task)
        object.__setattr__(self, "task", task.value)
        if (self.split is None) == (self.episode_file is None):
            raise ConfigError("give exactly one episode source: a split or an episode file")
        known = (*SPLITS, TEST_PROTOCOL_SPLIT)
        if self.split is not None and self.split not in known:
            raise ConfigError(f"unknown split {self.split!r}; choose one of: {', '.join(known)}")
        if self.split == TEST_PROTOCOL_SPLIT:
            episodes = TEST_PROTOCOL_EPISODES if self.episodes is None else self.episodes
            object.__setattr__(self, "episodes", episodes)
            if episodes > TEST_PROTOCOL_EPISODES or self.houses not in (None, 14):
                raise ConfigError(
                    f"split {TEST_PROTOCOL_SPLIT} is {TEST_PROTOCOL_EPISODES} episodes on the 14 "
                    "test houses; pass --episodes up to 500 and no --houses, or use --split test"
                )
        if self.episodes is not None and self.episodes < 1:
            raise ConfigError(f"--episodes must be at least 1, got {self.episodes}")
        if self.split is not None and self.houses is None:
            object.__setattr__(self, "houses", SPLIT_SIZES[source_split(self.split)])
        if self.episode_file is not None and self.houses is not None:
            raise ConfigError("--houses applies to built-in splits, not to an episode file")
        if self.houses is not None and self.houses < 1:
            raise ConfigError(f"--houses must be at least 1, got {self.houses}")
        if not all(isinstance(v, str) for v in self.agent_options.values()):
            raise ConfigError("agent options are NAME=VALUE strings")
        if self.max_steps < 1:
            raise ConfigError(f"--max-steps must be at least 1, got {self.max_steps}")
        if not self.budgets:
            raise ConfigError("give at least one dialog budget")
        if any(budget < 0 for budget in self.budgets):
            raise ConfigError(f"dialog budgets must be >= 0, got {list(self.budgets)}")
        if any(budget > MAX_DIALOG_BUDGET for budget in self.budgets):
            raise ConfigError(_budget_range_error(", ".join(map(str, self.budgets))))
        if len(set(self.budgets)) != len(self.budgets):
            raise ConfigError(f"dialog budgets repeat: {list(self.budgets)}")
        if not task.has_dialog and any(budget > 0 for budget in self.budgets):
            raise ConfigError(
                f"task {task.value} has no dialog, so its only budget is 0 "
                f"(got {list(self.budgets)}); drop --budget/--budgets or use --task iign or ign"
            )
        object.__setattr__(self, "detector", resolve_detector(self.agent, self.detector))
        preset(self.preset)

    def to_json(self) -> dict[str, Any]:
        data = asdict(self)
        data["budgets"] = list(self.budgets)
        data["shard"] = str(self.shard)
        data["agent_options"] = dict(sorted(self.agent_options.items()))
        return data

    @staticmethod
    def from_json(data: Any, where: str) -> EvalConfig:
        """Parse a ``run.json`` object; ``where`` names the file in errors."""
        if not isinstance(data, dict):
            raise DataFormatError(f"{where}: expected a JSON object of run arguments")
        try:
            values = dict(data)
            values["budgets"] = tuple(values["budgets"])
            values["shard"] = Shard.parse(values["shard"])
            values.setdefault("preset", SMALL.name)
            return EvalConfig(**values)
        except (KeyError, TypeError, ConfigError) as error:
            raise DataFormatError(f"{where}: malformed run arguments ({error})") from None


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
        if high > MAX_DIALOG_BUDGET:
            raise ConfigError(_budget_range_error(text))
        return tuple(range(low, high + 1))
    try:
        return tuple(int(part) for part in text.split(","))
    except ValueError:
        raise ConfigError(
            f"cannot read dialog budgets {text!r}; write a range (0-5) or a list (0,2,5)"
        ) from None


def _budget_range_error(given: str) -> str:
    """Why a budget above :data:`MAX_DIALOG_BUDGET` is refused, in one line."""
    return (
        f"dialog budgets run from 0 to {MAX_DIALOG_BUDGET}, the paper's range (its budget 5 "
        f"already lets an agent ask all it wants), got {given}; use e.g. --budgets 0-5"
    )


def describe_differences(stored: EvalConfig, wanted: EvalConfig) -> list[str]:
    """One ``name: stored there, wanted now`` line per argument that differs."""
    before, after = stored.to_json(), wanted.to_json()
    return [
        f"{name}: {before[name]!r} there, {after[name]!r} now"
        for name in before
        if before[name] != after[name]
    ]
