"""Commands whose flags are generated from a typed config (:class:`vlln.config.Config`).

Each field becomes one flag (``max_steps`` -> ``--max-steps``; a field's first validation
alias, when it has one, names the flag instead), its help text is the field's docstring and
its default the field's default; booleans get ``--x/--no-x``; a field marked
:class:`vlln.config.BareFlag` also takes its flag alone. The handler receives the built config,
so no command maps flags to settings by hand; a command whose work is library calls taking
that config names them with :class:`Calls` instead of a handler of its own.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module
from pathlib import Path
from typing import Any, TypeVar, get_args, get_origin

from pydantic_settings import CliSettingsSource

from vlln.cli.options import Commands
from vlln.config import BareFlag, Config
from vlln.errors import ConfigError, DataFormatError
from vlln.files import ReadCap, parse_json

C = TypeVar("C", bound=Config)

CONFIG_FLAG = "config"
"""``--config FILE``: settings stored by an earlier run, under the flags given."""


class _LazyParser(argparse.ArgumentParser):
    """A command's parser whose flags are added on first use (parsing it, its help, its
    defaults), so that ``vlln --help`` never imports the modules its configs live in."""

    fill: Callable[[argparse.ArgumentParser], None] | None = None

    def _filled(self) -> None:
        fill, self.fill = self.fill, None
        if fill is not None:
            fill(self)

    def parse_known_args(self, *args: Any, **kwargs: Any) -> Any:
        self._filled()
        return super().parse_known_args(*args, **kwargs)

    def format_help(self) -> str:
        self._filled()
        return super().format_help()

    def format_usage(self) -> str:
        self._filled()
        return super().format_usage()

    def get_default(self, dest: str) -> Any:
        self._filled()
        return super().get_default(dest)


@dataclass(frozen=True)
class Calls:
    """A command's handler that calls each ``"module:function"`` of ``targets`` with the
    config, in order, importing its module only when the command is used (so ``vlln --help``
    stays light), and returns 0."""

    targets: tuple[str, ...]

    def functions(self) -> list[Callable[[Config], object]]:
        """The functions named, imported."""
        found = []
        for target in self.targets:
            module, name = target.split(":")
            found.append(getattr(import_module(module), name))
        return found

    def __call__(self, config: Config) -> int:
        for function in self.functions():
            function(config)
        return 0


def calls(*targets: str) -> Calls:
    """The handler calling ``targets`` (``"module:function"``) with the command's config."""
    return Calls(targets)


def add_config_command(
    commands: Commands,
    name: str,
    config: type[C] | Callable[[], type[C]],
    handler: Callable[[C], int],
    help: str,
    replay: bool = False,
) -> argparse.ArgumentParser:
    """Add command ``name``, its flags generated from ``config`` (the class, or a function
    importing it when the command is used); ``handler`` gets the config built from the flags
    given (a :class:`Calls` handler is kept as the parser's ``calls`` default, so that its
    functions can be checked against the config). With ``replay``, ``--config FILE`` reads
    settings stored by :meth:`Config.to_json` (e.g. a run's ``run.json``) and the flags given
    override them."""
    parser_class = commands._parser_class
    commands._parser_class = _LazyParser
    try:
        # argparse %-formats a command's help in the list of commands, not its description
        parser = commands.add_parser(name, help=help.replace("%", "%%"), description=help)
    finally:
        commands._parser_class = parser_class
    assert isinstance(parser, _LazyParser)

    def fill(parser: argparse.ArgumentParser) -> None:
        config_class = config if isinstance(config, type) else config()
        if replay:
            parser.add_argument(
                "--" + CONFIG_FLAG,
                metavar="FILE",
                help="settings stored by an earlier run (its run.json); flags given override them",
            )
        source: CliSettingsSource[Any] = CliSettingsSource(
            config_class, root_parser=parser, add_argument_method=_argument_adder(config_class)
        )

        def run(args: argparse.Namespace) -> int:
            return handler(config_from_args(config_class, source, args))

        parser.set_defaults(
            handler=run,
            config_class=config_class,
            calls=handler if isinstance(handler, Calls) else None,
        )

    parser.fill = fill
    return parser


def config_from_args(
    config: type[C], source: CliSettingsSource[Any], args: argparse.Namespace
) -> C:
    """The config the parsed ``args`` give, over a ``--config`` file's settings if named."""
    given = {key: value for key, value in vars(args).items() if key != CONFIG_FLAG}
    paths = {name: given.pop(name) for name in _path_lists(config) if given.get(name) is not None}
    flags = source(parsed_args=argparse.Namespace(**given))() | paths
    stored_path = getattr(args, CONFIG_FLAG, None)
    if stored_path is None:
        return config.build(flags)
    stored = _read_settings(Path(stored_path))
    return config.build(config.replay(stored, stored_path, _by_field_name(config, flags)))


def _path_lists(config: type[Config]) -> list[str]:
    """Fields holding a list of paths: their words are taken as argparse split them, since
    pydantic-settings reads list items as JSON (``nan``, ``123``, ``true`` or ``null`` are no
    paths to it, and a comma splits one path in two)."""
    return [
        name
        for name, field in config.model_fields.items()
        if get_origin(field.annotation) is list and get_args(field.annotation) == (Path,)
    ]


def _argument_adder(config: type[Config]) -> Callable[..., argparse.Action]:
    """``parser.add_argument`` that lets the flag of a :class:`BareFlag` field go without a
    value (argparse's ``nargs="?"``, which pydantic-settings does not generate), and gives a
    boolean its first name alone: ``--json/--no-json``, not also ``--as-json/--no-as-json``
    for a field whose name is only there for Python."""
    bare = {
        name: marker.value
        for name, field in config.model_fields.items()
        for marker in field.metadata
        if isinstance(marker, BareFlag)
    }

    def add(parser: Any, *names: str, **kwargs: Any) -> argparse.Action:
        if kwargs.get("dest") in bare:
            kwargs.update(nargs="?", const=bare[kwargs["dest"]])
        if kwargs.get("action") is argparse.BooleanOptionalAction:
            names = names[:1]
        action: argparse.Action = parser.add_argument(*names, **kwargs)
        return action

    return add


def _by_field_name(config: type[Config], flags: dict[str, Any]) -> dict[str, Any]:
    """``flags`` keyed by field name, where a flag is named by its alias, so that it overrides
    the stored value of the same field."""
    names = {}
    for field_name, field in config.model_fields.items():
        alias = field.validation_alias
        for choice in getattr(alias, "choices", [alias] if alias else []):
            names[str(choice)] = field_name
    unknown = sorted(set(flags) - set(config.model_fields) - set(names))
    if unknown:
        raise ConfigError(f"unknown settings {', '.join(unknown)}")
    return {names.get(key, key): value for key, value in flags.items()}


# A settings file is a few hundred bytes; the cap stops ``--config /dev/zero`` at once.
_SETTINGS_CAP = ReadCap("a settings file", 1)


def _read_settings(path: Path) -> Any:
    """The JSON of a ``--config`` file; a missing, unreadable or endless one is one line."""
    try:
        return parse_json(_SETTINGS_CAP.read(path))
    except OSError as error:
        raise ConfigError(f"--config {path}: cannot read it ({error.strerror})") from None
    except DataFormatError as error:
        raise ConfigError(f"--config {path}: {error}") from None
