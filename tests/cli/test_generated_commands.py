"""Commands generated from typed configs: their flags, defaults and errors come from the config
class alone, and ``--config`` replays stored settings."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from collections.abc import Iterator
from enum import Enum
from pathlib import Path

import pytest
from pydantic import AliasChoices, BaseModel

from vlln.cli import build_parser, main
from vlln.cli.eval_configs import EvalCommand
from vlln.cli.generated import add_config_command
from vlln.config import Config
from vlln.train.config import TrainConfig

BENCH_COMMANDS = (
    "sim",
    "eval",
    "oracle",
    "agent",
    "storeys",
    "frontier-storeys",
    "data",
    "fidelity",
    "world",
)


def _commands(
    parser: argparse.ArgumentParser, path: tuple[str, ...] = ()
) -> Iterator[tuple[tuple[str, ...], argparse.ArgumentParser]]:
    """Every (sub)command of the parser tree, with its words."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield (*path, name), sub
                yield from _commands(sub, (*path, name))


def _generated() -> list[tuple[tuple[str, ...], argparse.ArgumentParser, type[Config]]]:
    found = []
    for words, parser in _commands(build_parser()):
        config = parser.get_default("config_class")
        if config is not None:
            found.append((words, parser, config))
    return found


def test_the_commands_with_settings_are_generated_from_their_configs() -> None:
    names = {" ".join(words) for words, _, _ in _generated()}
    assert {
        "train sft",
        "eval",
        "score",
        "report",
        "video",
        "demo",
        "data build",
        "data balance",
        "data export-sft",
        "data episodes",
        "data stats",
        "oracle classify-report",
        "oracle train-classifier",
        "train new-model",
        "train dialog-policy",
        "world show",
        "world export",
        "world import",
        "world catalogue",
        "oracle serve",
        "serve web",
        *(f"bench {name}" for name in BENCH_COMMANDS),
    } <= names


@pytest.mark.parametrize("words, parser, config", _generated(), ids=lambda v: str(v))
def test_every_flag_is_a_field_and_every_default_the_fields(
    words: tuple[str, ...], parser: argparse.ArgumentParser, config: type[Config]
) -> None:
    flags = {
        option: action
        for action in parser._actions
        for option in action.option_strings
        if option.startswith("--") and option not in ("--help", "--config")
    }
    positionals = {action.dest: action for action in parser._actions if not action.option_strings}
    for name, field in config.model_fields.items():
        if isinstance(field.default, BaseModel):
            continue
        if name in positionals:  # CliPositionalArg: required, so no default
            assert field.description and positionals[name].help == field.description
            continue
        alias = field.validation_alias
        first = alias.choices[0] if isinstance(alias, AliasChoices) else alias or name
        flag = "--" + str(first).replace("_", "-")
        assert flag in flags, f"{' '.join(words)}: field {name} has no flag {flag}"
        help_text = (flags[flag].help or "").replace("\n", " ")
        assert field.description or field.is_required(), f"{name} has no docstring"
        if field.default_factory is not None:
            shown = f"(default factory: {field.default_factory.__name__})"
            assert shown in help_text, f"{' '.join(words)} {flag}: {help_text}"
        elif not field.is_required():
            # pydantic-settings names an enum default by its member name (flags take both)
            default = field.default.name if isinstance(field.default, Enum) else field.default
            assert f"(default: {default})" in help_text or (
                isinstance(field.default, tuple | list)
            ), f"{' '.join(words)} {flag}: help shows no default {field.default!r}: {help_text}"
        # The argparse-level default is never a second copy of the value.
        assert flags[flag].default in (None, argparse.SUPPRESS, False), (
            f"{' '.join(words)} {flag} has its own default {flags[flag].default!r}"
        )


@pytest.mark.parametrize("words, parser, config", _generated(), ids=lambda v: str(v))
def test_help_names_each_flag_once_and_shows_percent_signs_as_written(
    words: tuple[str, ...], parser: argparse.ArgumentParser, config: type[Config]
) -> None:
    text = parser.format_help()
    assert "%%" not in text and "--as-json" not in text
    booleans = [a for a in parser._actions if isinstance(a, argparse.BooleanOptionalAction)]
    assert all(len(action.option_strings) == 2 for action in booleans)  # --x and --no-x


def test_train_flags_build_the_config_and_bad_values_are_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["train", "sft", "--data", "d", "--model", "m", "--out", "o", "--lr", "-1"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.strip() == "error: --lr: Input should be greater than 0"
    code = main(["train", "sft", "--model", "m"])
    assert capsys.readouterr().err.strip() == "error: --data: required; --out: required"


def test_stored_settings_read_back_equal_and_refuse_unknown_keys(tmp_path: Path) -> None:
    config = TrainConfig.build({"data": "d", "model": "m", "out": "o", "lr": 0.5, "lora": True})
    stored = json.loads(json.dumps(config.to_json()))
    assert TrainConfig.from_json(stored, "x.json") == config
    with pytest.raises(Exception, match=r"x.json: malformed settings \(learnig_rate: not a known"):
        TrainConfig.from_json({**stored, "learnig_rate": 1.0}, "x.json")


def test_the_parser_imports_no_config_module_until_a_command_is_used() -> None:
    code = (
        "import sys; from vlln.cli import build_parser; build_parser(); print(sorted(m for m "
        "in sys.modules if m.startswith(('vlln.datagen', 'vlln.oracle_service'))))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"
    parser = build_parser()
    parser.parse_args(["data", "build", "--houses", "1", "--out", "o"])
    assert "vlln.cli.data_settings" in sys.modules


def test_data_episodes_refuses_floors_for_houses_that_draw_their_own(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["data", "episodes", "--houses", "1", "--out", "o", "--floors", "2"]) == 2
    assert capsys.readouterr().err.strip() == (
        "error: --floors sets the storeys of small houses; mp3d houses draw theirs from the "
        "seed: add --preset small, or drop --floors"
    )


def test_a_bare_flag_goes_without_its_value_and_eval_keeps_its_flag_spellings() -> None:
    parser = argparse.ArgumentParser()
    built: list[EvalCommand] = []

    def keep(config: EvalCommand) -> int:
        built.append(config)
        return 0

    add_config_command(parser.add_subparsers(), "eval", EvalCommand, keep, help="", replay=True)
    common = ["eval", "--agent", "frontier", "--task", "iign", "--out", "o", "--preset", "small"]
    for given, ray in (([], None), (["--ray"], ""), (["--ray", "auto"], "auto")):
        args = parser.parse_args([*common, *given, "--budget", "0", "--no-sweep"])
        assert args.handler(args) == 0
        assert (built[-1].ray, built[-1].budgets, built[-1].sweep) == (ray, (0,), False)
