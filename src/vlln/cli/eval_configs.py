"""The settings of ``vlln eval``, ``score``, ``report``, ``video`` and ``demo``.

``vlln eval``'s config is the run's own (:class:`vlln.eval.config.EvalConfig`, stored as
``run.json``) plus how to run it this time (where, how many now, on Ray or not), which never
changes an episode line. The model flags (``--base-url``, ``--model-timeout``, ...) are the
agent's options flattened onto the command line: each is an option's name or alias in the
agent's options class (:data:`vlln.agents.registry.OPTIONS`), where their defaults live.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

from pydantic import AliasChoices, Field, model_validator
from pydantic_settings import CliPositionalArg, SettingsConfigDict

from vlln.cluster.options import RayChunkOptions, ServingOptions
from vlln.config import Config
from vlln.eval.config import EvalConfig
from vlln.eval.options import Radii, ReportOptions

MODEL_FLAGS = (
    "base_url",
    "model",
    "api_key_env",
    "model_timeout",
    "model_retries",
    "model_max_failures",
    "model_cache",
    "device",
    "max_tokens",
    "dialog_policy",
)
"""The fields of :class:`EvalCommand` that are agent options (by option name or alias)."""


class EvalCommand(EvalConfig, RayChunkOptions, ServingOptions):
    """``vlln eval``: the run's settings, and how to run it now (``--ray``, ``--chunk`` and
    ``--retries`` from :class:`RayChunkOptions`)."""

    model_config = SettingsConfigDict(protected_namespaces=())

    out: Path
    """run directory (resumed when it exists)"""
    budget: int | None = None
    """one dialog budget (the same as --budgets N)"""
    cache_dir: Path | None = None
    """where built splits are kept (none: ~/.cache/vlln)"""
    stop_after: int | None = Field(None, ge=0)
    """play at most N episodes now, then stop (a rerun goes on)"""
    quiet: bool = False
    """no progress bar"""
    sweep: bool = True
    """play an episode's budgets together, sharing prefixes (--no-sweep: each on its own;
    the same records, slower)"""
    concurrent: Annotated[int, Field(ge=1)] = 1
    """vlln: episodes played side by side in this process, their model calls answered in
    batches of up to N (the same records, faster on a GPU); never stored in run.json"""
    base_url: str | None = None
    """openai-vlm, aiuta: the OpenAI-compatible server, e.g. http://localhost:8000/v1"""
    model: str | None = None
    """openai-vlm, aiuta: the served model's name; vlln: its folder"""
    api_key_env: str | None = None
    """openai-vlm, aiuta: the variable holding the API key (none: the agent's default)"""
    model_timeout: float | None = None
    """openai-vlm, aiuta: deadline of each whole request in s (none: the agent's default)"""
    model_retries: int | None = None
    """openai-vlm, aiuta: retries per request (none: the agent's default)"""
    model_max_failures: int | None = None
    """openai-vlm, aiuta: failed requests in a row that stop the run (none: the agent's
    default, 4)"""
    model_cache: str | None = None
    """openai-vlm, aiuta: folder caching model replies (none: no cache)"""
    device: str | None = None
    """vlln: torch device (none: cuda if present, else cpu)"""
    max_tokens: int | None = None
    """openai-vlm, vlln: longest model reply in tokens (none: the agent's default)"""
    dialog_policy: str | None = None
    """frontier: when to ask, a folder made by vlln train dialog-policy (none: the fixed
    triggers)"""

    @model_validator(mode="before")
    @classmethod
    def _fold_flags(cls, data: Any) -> Any:
        """``--budget N`` is ``--budgets N`` (giving both is refused); the model flags given
        become the agent's options, over options stored in a replayed run.json."""
        if not isinstance(data, dict):
            return data
        data = dict(data)
        if data.get("budget") is not None:
            if data.get("budgets") is not None:
                raise ValueError("give --budget or --budgets, not both")
            data["budgets"] = data["budget"]
        flags = {name: data[name] for name in MODEL_FLAGS if data.get(name) is not None}
        if flags:
            stored = data.get("agent_options") or {}
            if not isinstance(stored, dict):
                stored = stored.to_json()
            data["agent_options"] = {**_by_option_name(str(data.get("agent")), stored), **flags}
        return data

    @classmethod
    def replay(cls, stored: Any, where: str, given: dict[str, Any]) -> dict[str, Any]:
        """The run of ``stored`` (a run.json) under the flags ``given``; a flag replaces the
        stored settings it excludes (``--budget`` the budgets, ``--episode-file`` the split,
        ``--agent`` the agent's options and detector)."""
        run = EvalConfig.from_json(stored, where).to_json()
        replaced = {
            "budget": ("budgets",),
            "episode_file": ("split", "houses"),
            "split": ("episode_file",),
            "agent": ("agent_options", "detector"),
        }
        for flag, names in replaced.items():
            if flag in given:
                for name in names:
                    run.pop(name, None)
        return run | given


def _by_option_name(agent: str, options: dict[str, Any]) -> dict[str, Any]:
    """Stored options keyed so that a model flag (an option's alias) replaces its option."""
    from vlln.agents.registry import OPTIONS

    known = OPTIONS.get(agent)
    if known is None:
        return options
    names = known.names()
    flags = {field: name for name, field in names.items() if name in MODEL_FLAGS}
    return {flags.get(names.get(key, key), key): value for key, value in options.items()}


class ScoreCommand(Radii):
    """``vlln score``: every metric recomputed from run directories."""

    dirs: CliPositionalArg[list[Path]]
    """run directories (e.g. the shards of one run)"""
    as_json: bool = Field(False, validation_alias=AliasChoices("json", "as_json"))
    """print the summary as JSON"""


class ReportCommand(ReportOptions):
    """``vlln report``: report.md and report.html of run directories."""

    dirs: CliPositionalArg[list[Path]]
    """run directories, compared side by side"""
    out: Path | None = None
    """report directory (none: DIR/report for one run, else ./report)"""


class VideoCommand(Config):
    """``vlln video``: an MP4 of an episode: view, map, dialog captions."""

    source: CliPositionalArg[Path]
    """a run directory, a results .jsonl or a record .json"""
    episode: str | None = None
    """episode id (none: the one with the most dialog)"""
    budget: int | None = None
    """dialog budget (none: the largest)"""
    out: Path | None = None
    """MP4 file (none: SOURCE_DIR/videos/video_<id>_b<k>.mp4)"""
    scenes: Path | None = None
    """folder of scanned scenes (none: the run's --scenes)"""


class DemoCommand(Config):
    """``vlln demo``: the main job on the built-in houses."""

    out: Path = Path("out/demo")
    """output directory"""
