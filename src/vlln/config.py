"""Typed configs: the one place a command's settings, their defaults and their checks live.

Every command's settings are a :class:`Config` (pydantic-settings). The command line is
generated from the class (:mod:`vlln.cli.generated`: one flag per field, its help text the
field's docstring, its default the field's default), files such as ``run.json`` are written
with :meth:`Config.to_json` and read back with :meth:`Config.from_json`, and every check is a
pydantic validator. So a default or a rule is written once, and a stored run replays exactly.
Settings built in code rather than from flags (an agent's tuning, a camera, a server) are
:func:`settings_dataclass` classes, checked the same way; only value objects built in hot loops
guard themselves in ``__post_init__``, each saying so.

pydantic-settings was chosen over tyro and draccus because pydantic already validates the web
app's and the oracle service's request bodies: one validation style everywhere, and its
command-line source attaches to an existing argparse tree, so commands without settings stay
plain argparse.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Annotated, Any, ClassVar, Self, TypeVar, dataclass_transform

from pydantic import Field, ValidationError
from pydantic.dataclasses import dataclass as pydantic_dataclass
from pydantic_settings import BaseSettings, PydanticBaseSettingsSource, SettingsConfigDict

from vlln.errors import ConfigError, DataFormatError

__all__ = [
    "BareFlag",
    "Config",
    "Count",
    "Positive",
    "Probability",
    "SettingsError",
    "describe_validation_error",
    "settings_dataclass",
]

_T = TypeVar("_T")

Count = Annotated[int, Field(ge=1)]
"""A whole number of at least 1 (steps, pixels, houses)."""
Positive = Annotated[float, Field(gt=0.0)]
"""A number above 0 (metres, seconds)."""
Probability = Annotated[float, Field(ge=0.0, le=1.0)]
"""A number in [0, 1]."""


class Config(BaseSettings):
    """Base of every typed config: frozen, unknown keys refused, read from its arguments only
    (never from environment variables or ``.env`` files, so a run depends on what was given)."""

    model_config = SettingsConfigDict(
        frozen=True,
        extra="forbid",
        populate_by_name=True,
        use_attribute_docstrings=True,
        cli_kebab_case=True,
        cli_implicit_flags=True,
        cli_hide_none_type=True,
        cli_avoid_json=True,
    )

    file_keys: ClassVar[tuple[str, ...]] = ()
    """Keys a stored file may hold beside the settings (written by the runner, not settings)."""
    unrecorded_at_default: ClassVar[tuple[str, ...]] = ()
    """Settings added after files were first stored: left out of :meth:`to_json` at their
    defaults, so those files are written (and resumed) byte for byte as before."""

    @classmethod
    def settings_customise_sources(
        cls,
        settings_cls: type[BaseSettings],
        init_settings: PydanticBaseSettingsSource,
        env_settings: PydanticBaseSettingsSource,
        dotenv_settings: PydanticBaseSettingsSource,
        file_secret_settings: PydanticBaseSettingsSource,
    ) -> tuple[PydanticBaseSettingsSource, ...]:
        return (init_settings,)

    def __init__(self, **values: Any) -> None:
        """The config of ``values``; invalid ones raise :class:`SettingsError`, one line that
        names each flag at fault (never pydantic's multi-line report)."""
        try:
            super().__init__(**values)
        except ValidationError as error:
            raise SettingsError(error) from None

    @classmethod
    def build(cls, values: dict[str, Any], flags: bool = True) -> Self:
        """The config of ``values``; an invalid value raises :class:`ConfigError` in one line
        that names the flag (``flags``) or the key at fault."""
        try:
            return cls(**values)
        except SettingsError as error:
            if flags:
                raise
            raise ConfigError(describe_validation_error(error.error, False)) from None

    @classmethod
    def replay(cls, stored: Any, where: str, given: dict[str, Any]) -> dict[str, Any]:
        """The values of a command replaying the settings ``stored`` in file ``where`` (read
        with :meth:`from_json`) under the flags ``given`` (keyed by field name)."""
        return cls.from_json(stored, where).to_json() | given

    def replace(self, **changes: Any) -> Self:
        """A copy with ``changes``, checked like a new config (``dataclasses.replace``)."""
        return type(self)(**(self.model_dump() | changes))

    def to_json(self) -> dict[str, Any]:
        """The settings as JSON values, in field order (what ``run.json`` and friends store),
        less those of :attr:`unrecorded_at_default` that are at their defaults."""
        fields = self.model_dump(mode="json")
        for name in self.unrecorded_at_default:
            if getattr(self, name) == type(self).model_fields[name].default:
                del fields[name]
        return fields

    @classmethod
    def from_json(cls, data: Any, where: str) -> Self:
        """Read settings stored by :meth:`to_json`; ``where`` names the file in errors. Keys in
        :attr:`file_keys` are the file's own and are skipped."""
        if not isinstance(data, dict):
            raise DataFormatError(f"{where}: expected a JSON object of settings")
        values = {key: value for key, value in data.items() if key not in cls.file_keys}
        try:
            return cls(**values)
        except SettingsError as error:
            raise DataFormatError(
                f"{where}: malformed settings ({describe_validation_error(error.error, False)})"
            ) from None


class SettingsError(ConfigError):
    """Settings that do not validate; the message names each flag at fault, and ``error``
    keeps pydantic's report for other wordings (a file's keys)."""

    def __init__(self, error: ValidationError) -> None:
        super().__init__(describe_validation_error(error, True))
        self.error = error


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field, Field))
def settings_dataclass(cls: type[_T]) -> type[_T]:
    """``cls`` as a frozen pydantic dataclass: settings built in code (positionally, with
    ``dataclasses.replace``) rather than from flags, whose ``Field`` constraints and validators
    are their checks; an invalid value raises :class:`ConfigError` naming the field."""
    checked: Any = pydantic_dataclass(frozen=True)(cls)
    init = checked.__init__

    @functools.wraps(init)
    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        try:
            init(self, *args, **kwargs)
        except ValidationError as error:
            problems = describe_validation_error(error, False)
            raise ConfigError(f"{cls.__name__}: {problems}") from None

    checked.__init__ = __init__
    return checked


@dataclass(frozen=True)
class BareFlag:
    """Marks a field (``Annotated[str | None, BareFlag("")]``) whose flag may be given without
    a value, which then means ``value``: ``--ray`` alone as well as ``--ray ADDRESS``."""

    value: str


def describe_validation_error(error: ValidationError, flags: bool) -> str:
    """One line per problem, joined: ``--max-steps: must be at least 1`` (or the bare key when
    ``flags`` is false); pydantic's "Value error, " prefix is dropped from our own messages."""
    parts = []
    for problem in error.errors():
        if problem["type"] == "default_factory_not_called":
            continue  # a consequence of another field's error, reported on its own
        message = str(problem["msg"]).removeprefix("Value error, ")
        names = [str(part) for part in problem["loc"] if not isinstance(part, int)]
        if not names:
            parts.append(message)
            continue
        name = ".".join(names)
        shown = "--" + name.replace("_", "-") if flags else name
        if problem["type"] == "extra_forbidden":
            message = "not a known setting"
        elif problem["type"] == "missing":
            message = "required"
        parts.append(f"{shown}: {message}")
    return "; ".join(parts)
