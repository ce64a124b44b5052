"""Agents of one's own, named ``package.module:Class`` (``vlln eval --agent``; docs/own-agent.md).

The class is imported, made with the agent's seed like the built-in agents, and checked
against :class:`vlln.agents.protocol.Agent`; each way of getting this wrong is one line that
says what to fix.
"""

from __future__ import annotations

import importlib
import inspect
import os
import sys
from typing import cast

from vlln.agents.protocol import Agent
from vlln.errors import ConfigError

GUIDE = "docs/own-agent.md"
_METHODS = ("reset", "act")


def is_agent_spec(name: str) -> bool:
    """Whether ``name`` names a class (``module:Class``) rather than a built-in agent."""
    return ":" in name


def load_agent(spec: str, seed: int) -> Agent:
    """A fresh agent of the class ``spec`` names, made as ``Class(seed)``."""
    cls = _load_class(spec)
    try:
        agent = cls(seed)
    except Exception as error:
        raise ConfigError(
            f"--agent {spec}: {cls.__name__}(seed) failed: {_one_line(error)}"
        ) from None
    missing = [name for name in _METHODS if not callable(getattr(agent, name, None))]
    if not isinstance(getattr(agent, "name", None), str):
        missing.append("name (a str)")
    if not isinstance(getattr(agent, "privileged", None), bool):
        missing.append("privileged (a bool)")
    if missing:
        raise ConfigError(
            f"--agent {spec}: {cls.__name__} does not implement the agent protocol "
            f"(vlln.agents.protocol.Agent); it lacks {', '.join(missing)}; see {GUIDE}"
        )
    return cast(Agent, agent)


def _load_class(spec: str) -> type:
    module_name, _, class_name = spec.partition(":")
    if not module_name or not class_name or ":" in class_name:
        raise ConfigError(
            f"--agent {spec!r}: name an agent class as package.module:Class, e.g. "
            f"my_agents:MyAgent; see {GUIDE}"
        )
    module = _import(spec, module_name)
    cls = getattr(module, class_name, None)
    if cls is None:
        classes = sorted(name for name, value in vars(module).items() if inspect.isclass(value))
        defined = f"; it has: {', '.join(classes)}" if classes else "; it defines no classes"
        raise ConfigError(f"--agent {spec}: module {module_name} has no {class_name}{defined}")
    if not inspect.isclass(cls):
        raise ConfigError(f"--agent {spec}: {class_name} in {module_name} is not a class")
    return cast(type, cls)


def _import(spec: str, module_name: str) -> object:
    """Import ``module_name`` with the current folder on the path, as ``python -m`` has it."""
    here = os.getcwd()
    if here not in sys.path and "" not in sys.path:
        sys.path.append(here)
    try:
        return importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        if error.name == module_name or module_name.startswith(f"{error.name}."):
            raise ConfigError(
                f"--agent {spec}: no module named {module_name}; run from the folder that "
                "holds it, add that folder to PYTHONPATH, or install its package"
            ) from None
        raise ConfigError(f"--agent {spec}: importing {module_name} failed: {error}") from None
    except Exception as error:
        raise ConfigError(
            f"--agent {spec}: importing {module_name} failed: {_one_line(error)}"
        ) from None


def _one_line(error: BaseException) -> str:
    text = " ".join(str(error).split())
    return f"{type(error).__name__}: {text}" if text else type(error).__name__
