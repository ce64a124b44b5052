"""``vlln serve web``: its flags come from :class:`vlln.web.settings.ServeWebCommand`; the
handler imports the heavy parts, so ``vlln --help`` stays fast."""

from __future__ import annotations

import os
from dataclasses import replace
from typing import TYPE_CHECKING

from vlln.cli.generated import add_config_command
from vlln.cli.options import Commands

if TYPE_CHECKING:
    from vlln.agents.options import AgentOptions
    from vlln.web.settings import ServeWebCommand

DEFAULT_SPLIT = "test"


def _serve_web_command() -> type[ServeWebCommand]:
    from vlln.web.settings import ServeWebCommand

    return ServeWebCommand


def _serve_web(command: ServeWebCommand) -> int:
    from vlln.extras import SERVE_PACKAGES, require_extra

    require_extra("serve", "vlln serve web", SERVE_PACKAGES)
    from vlln.errors import ConfigError
    from vlln.eval.runner import order_by_scene, spread_over_scenes
    from vlln.http.addresses import is_loopback
    from vlln.oracle.llm.openai_client import OpenAISettings
    from vlln.tasks.episode import read_episodes
    from vlln.tasks.split_files import default_cache_dir, load_or_build_split
    from vlln.tasks.splits import SPLIT_SIZES
    from vlln.web.config import WebConfig, WebLimits
    from vlln.web.server import episode_source, serve

    token = os.environ.get(command.token_env) or None
    if token is None and not is_loopback(command.host):  # before building any house
        raise ConfigError(
            f"host {command.host!r} is not a loopback address; serving the study beyond this "
            f"machine needs an access token: set {command.token_env} (16+ characters)"
        )
    split = command.split or DEFAULT_SPLIT
    houses = command.houses or SPLIT_SIZES.get(split, 1)
    if command.episode_file is not None:
        episodes = read_episodes(command.episode_file)
    else:
        cache = command.cache_dir or default_cache_dir()
        episodes = load_or_build_split(split, command.task, houses, cache, preset=command.preset)
    episodes = order_by_scene(episodes)
    if command.episodes is not None:
        episodes = spread_over_scenes(episodes, command.episodes)
    llm = None
    if command.llm_model:
        llm = OpenAISettings(model=command.llm_model)
        if command.llm_base_url:
            llm = replace(llm, base_url=command.llm_base_url)
    budget = command.task.default_budget if command.budget is None else command.budget
    config = WebConfig.build(
        {
            **command.model_dump(include=set(WebLimits.model_fields)),
            "episodes": tuple(episodes),
            "out": command.out,
            "dialog_budget": budget,
            "token": token,
            "llm": llm,
            "agent_options": _agent_options(command.agent_option),
        },
        flags=False,
    )
    source = episode_source(command.episode_file, split, houses)
    if command.episodes is not None:
        source += f", {command.episodes} episodes"
    serve(config, command.host, command.port, source)
    return 0


def _agent_options(given: tuple[str, ...]) -> dict[str, AgentOptions]:
    """``AGENT.KEY=VALUE`` settings, e.g. ``openai-vlm.base_url=http://127.0.0.1:8000/v1``,
    read into each agent's options class (a bad one is one line naming the agent)."""
    from vlln.agents.registry import agent_options
    from vlln.errors import ConfigError

    options: dict[str, dict[str, str]] = {}
    for item in given:
        name, dot, rest = item.partition(".")
        key, equals, value = rest.partition("=")
        if not (dot and equals and name and key):
            raise ConfigError(f"--agent-option {item!r} is not AGENT.KEY=VALUE")
        options.setdefault(name, {})[key] = value
    return {name: agent_options(name, values) for name, values in options.items()}


def add_serve_commands(commands: Commands) -> None:
    """``vlln serve web``."""
    serve = commands.add_parser("serve", help="web pages for people").add_subparsers(
        dest="serve_command", required=True
    )
    add_config_command(
        serve,
        "web",
        _serve_web_command,
        _serve_web,
        help="navigate or answer in the browser (human studies)",
    )
