"""``vlln serve web``: argument definitions and the handler (imports of the heavy parts happen
inside the handler, so ``vlln --help`` stays fast)."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

Commands = argparse._SubParsersAction


def _serve_web(args: argparse.Namespace) -> int:
    from vlln.extras import SERVE_PACKAGES, require_extra

    require_extra("serve", "vlln serve web", SERVE_PACKAGES)
    from vlln.errors import ConfigError
    from vlln.eval.runner import default_cache_dir, order_by_scene, spread_over_scenes
    from vlln.http.addresses import is_loopback
    from vlln.oracle.llm.openai_client import OpenAISettings
    from vlln.tasks.episode import read_episodes
    from vlln.tasks.spec import TaskType
    from vlln.tasks.split_files import load_or_build_split
    from vlln.tasks.splits import SPLIT_SIZES
    from vlln.web.config import WebConfig
    from vlln.web.server import episode_source, serve

    token = os.environ.get(args.token_env) or None
    if token is None and not is_loopback(args.host):  # before building any house
        raise ConfigError(
            f"host {args.host!r} is not a loopback address; serving the study beyond this "
            f"machine needs an access token: set {args.token_env} (16+ characters)"
        )
    task = TaskType.parse(args.task)
    episode_file = None if args.episode_file is None else Path(args.episode_file)
    houses = args.houses or SPLIT_SIZES.get(args.split, 1)
    if episode_file is not None:
        episodes = read_episodes(episode_file)
    else:
        cache = Path(args.cache_dir) if args.cache_dir else default_cache_dir()
        episodes = load_or_build_split(args.split, task, houses, cache)
    episodes = order_by_scene(episodes)
    if args.episodes is not None:
        episodes = spread_over_scenes(episodes, args.episodes)
    llm = None
    if args.llm_model:
        llm = OpenAISettings(model=args.llm_model, base_url=args.llm_base_url)
    budget = args.budget if args.budget is not None else (5 if task == TaskType.IIGN else 0)
    config = WebConfig(
        episodes=tuple(episodes),
        out=Path(args.out),
        task=task,
        dialog_budget=budget,
        max_steps=args.max_steps,
        seed=args.seed,
        token=token,
        answer_time_limit_s=args.answer_time_limit,
        idle_limit_s=args.idle_limit,
        max_live_sessions=args.max_sessions,
        llm=llm,
        agent_options=_agent_options(args.agent_option),
    )
    source = episode_source(episode_file, args.split, houses)
    if args.episodes is not None:
        source += f", {args.episodes} episodes"
    serve(config, args.host, args.port, source)
    return 0


def _agent_options(given: list[str]) -> dict[str, dict[str, str]]:
    """``AGENT.KEY=VALUE`` settings, e.g. ``openai-vlm.base_url=http://127.0.0.1:8000/v1``."""
    from vlln.errors import ConfigError

    options: dict[str, dict[str, str]] = {}
    for item in given:
        name, dot, rest = item.partition(".")
        key, equals, value = rest.partition("=")
        if not (dot and equals and name and key):
            raise ConfigError(f"--agent-option {item!r} is not AGENT.KEY=VALUE")
        options.setdefault(name, {})[key] = value
    return options


def add_serve_commands(commands: Commands) -> None:
    """``vlln serve web``."""
    serve = commands.add_parser("serve", help="web pages for people").add_subparsers(
        dest="serve_command", required=True
    )
    web = serve.add_parser("web", help="navigate or answer in the browser (human studies)")
    source = web.add_mutually_exclusive_group()
    source.add_argument("--split", default="test", help="built-in split (default test)")
    source.add_argument("--episode-file", help="released-format episode file (.json.gz)")
    web.add_argument("--houses", type=int, help="houses of the split (default: all of it)")
    web.add_argument("--episodes", type=int, help="serve N episodes spread over the houses")
    web.add_argument("--task", default="iign", help="iign (default), ign or objectnav")
    web.add_argument("--budget", type=int, help="answered questions (default 5 on IIGN)")
    web.add_argument("--max-steps", type=int, default=500, help="counted-step cap (500)")
    web.add_argument("--out", required=True, help="output folder (episode records; resumed)")
    web.add_argument("--host", default="127.0.0.1", help="address (default loopback only)")
    web.add_argument("--port", type=int, default=8770, help="port (default 8770)")
    web.add_argument(
        "--token-env",
        default="VLLN_WEB_TOKEN",
        help="environment variable with the access token; required off loopback "
        "(default VLLN_WEB_TOKEN)",
    )
    web.add_argument("--seed", type=int, default=0, help="seed of oracles and agents")
    web.add_argument(
        "--answer-time-limit", type=float, default=90.0, help="seconds a person has to answer"
    )
    web.add_argument(
        "--idle-limit", type=float, default=1800.0, help="seconds without action -> abandoned"
    )
    web.add_argument("--max-sessions", type=int, default=8, help="sessions played at once")
    web.add_argument("--llm-model", help="offer the language-model oracle with this model")
    web.add_argument(
        "--llm-base-url", default="https://api.openai.com/v1", help="its OpenAI-compatible URL"
    )
    web.add_argument(
        "--agent-option",
        action="append",
        default=[],
        metavar="AGENT.KEY=VALUE",
        help="offer an agent that takes options, e.g. openai-vlm.base_url=URL and "
        "openai-vlm.model=NAME (repeatable)",
    )
    web.add_argument("--cache-dir", help="where built splits are kept (default ~/.cache/vlln)")
    web.set_defaults(handler=_serve_web)
