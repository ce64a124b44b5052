"""A setting's default is written once, in its config: a function that a generated command
calls with its config declares no keyword default for a name that is a field of that config,
and the ``vlln bench`` functions take their settings class rather than loose keywords."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import typing
from collections.abc import Callable, Iterator

import vlln.bench
from tests.cli.test_generated_commands import BENCH_COMMANDS, _generated
from vlln.bench.settings import StoreysBench
from vlln.config import Config


def second_defaults(function: Callable[..., object], config: type[Config]) -> list[str]:
    """The parameters of ``function`` with a default whose name is a field of ``config``."""
    return [
        name
        for name, parameter in inspect.signature(function).parameters.items()
        if parameter.default is not inspect.Parameter.empty and name in config.model_fields
    ]


def _called() -> Iterator[tuple[str, Callable[..., object], type[Config]]]:
    """Each command that names its library calls, each function it calls and its config."""
    for words, parser, config in _generated():
        calls = parser.get_default("calls")
        if calls is not None:
            for function in calls.functions():
                yield " ".join(words), function, config


def test_every_bench_command_names_the_functions_it_calls() -> None:
    named = {command for command, _, _ in _called() if command.startswith("bench ")}
    assert named >= {f"bench {name}" for name in (*BENCH_COMMANDS, "web")}


def test_the_functions_commands_call_take_the_config_and_restate_no_default() -> None:
    for command, function, config in _called():
        first = next(iter(inspect.signature(function).parameters))
        taken = typing.get_type_hints(function)[first]
        assert issubclass(config, taken), f"{command}: {function.__name__} takes {taken}"
        assert second_defaults(function, config) == [], f"{command}: {function.__name__}"


def test_the_check_finds_a_restated_default() -> None:
    def restating(settings: StoreysBench, houses: int = 10, rng_seed: int = 0) -> None:
        del settings, houses, rng_seed

    assert second_defaults(restating, StoreysBench) == ["houses"]


def test_no_bench_function_restates_a_default_of_the_settings_it_takes() -> None:
    checked = 0
    for module_info in pkgutil.iter_modules(vlln.bench.__path__, "vlln.bench."):
        module = importlib.import_module(module_info.name)
        for function in vars(module).values():
            if not inspect.isfunction(function) or function.__module__ != module.__name__:
                continue
            for taken in typing.get_type_hints(function).values():
                if inspect.isclass(taken) and issubclass(taken, Config):
                    checked += 1
                    assert second_defaults(function, taken) == [], function.__qualname__
    assert checked >= len(BENCH_COMMANDS)
