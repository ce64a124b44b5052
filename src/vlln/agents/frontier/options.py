"""The frontier agent's one option: a learned dialog policy (``vlln eval --dialog-policy P``).

Without it the agent asks on its fixed triggers, as it always did, and ``run.json`` stores no
option at all, so such runs are unchanged. The folder is read when the option is checked, so a
missing or wrong one is refused before any episode is played.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

from pydantic import AfterValidator

from vlln.agents.frontier.agent import FrontierAgent
from vlln.agents.frontier.learned import load_policy
from vlln.agents.options import AgentOptions


def _policy_folder(path: str | None) -> str | None:
    """The folder's absolute path, once its policy loads (a ConfigError line otherwise)."""
    if path is None:
        return None
    folder = str(Path(path).expanduser().resolve())
    load_policy(folder)
    return folder


class FrontierOptions(AgentOptions):
    """Which dialog policy the frontier agent asks with."""

    dialog_policy: Annotated[str | None, AfterValidator(_policy_folder)] = None
    """a folder made by vlln train dialog-policy (none: the fixed triggers)"""


def frontier_agent(seed: int, options: FrontierOptions, detector: str = "truth") -> FrontierAgent:
    """The frontier agent, asking with the options' dialog policy."""
    folder = options.dialog_policy
    policy = None if folder is None else load_policy(folder)
    return FrontierAgent(seed, detector=detector, dialog_policy=policy)
