"""Type and range checks of a JSON object against a record dataclass, before it is built.

A results line that is valid JSON can still say ``"steps": "lots"`` or ``"budget": -3``; such a
value must be reported where it is (the field, and by the caller the file and line), never
reach the metrics as a ``TypeError``. The checks follow the dataclass's own type hints, so a
field added to a record later is checked without touching this module. Ranges: every integer
and every number is >= 0 and finite, except in ``signed`` fields (positions); an integer is at
most :data:`MAX_INTEGER` (a count or an id, exact in a float, so no metric overflows);
``None`` stands for an unreachable distance where the hint allows it.
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from collections.abc import Collection
from typing import Any

from vlln.errors import DataFormatError

MAX_INTEGER = 2**53 - 1


def check_object(
    cls: type[Any],
    data: Any,
    where: str = "",
    *,
    signed: Collection[str] = (),
    non_empty: Collection[str] = (),
    nullable: Collection[str] = (),
) -> None:
    """Raise :class:`DataFormatError` naming the first field of ``data`` that ``cls`` rejects.

    ``where`` prefixes field names of nested objects (``dialog[0].``); ``non_empty`` names
    string fields that may not be empty and ``nullable`` number fields whose items may be
    null (an unreachable distance, written as null since JSON has no infinity).
    """
    if not isinstance(data, dict):
        raise DataFormatError(f"field '{where.rstrip('.')}' must be an object, got {data!r:.60}")
    hints = _hints(cls)
    for name in data:
        if name not in hints:
            raise DataFormatError(f"unknown field '{where}{name}'")
    for item in dataclasses.fields(cls):
        if item.name not in data:
            required = (
                item.default is dataclasses.MISSING and item.default_factory is dataclasses.MISSING
            )
            if required:
                raise DataFormatError(f"missing field '{where}{item.name}'")
            continue
        _check_value(
            hints[item.name],
            data[item.name],
            f"{where}{item.name}",
            _Rules(item.name in signed, item.name in non_empty, item.name in nullable),
        )


_HINTS: dict[type[Any], dict[str, Any]] = {}


def _hints(cls: type[Any]) -> dict[str, Any]:
    if cls not in _HINTS:
        _HINTS[cls] = typing.get_type_hints(cls)
    return _HINTS[cls]


@dataclasses.dataclass(frozen=True)
class _Rules:
    signed: bool = False
    non_empty: bool = False
    nullable: bool = False


def _check_value(hint: Any, value: Any, name: str, rules: _Rules) -> None:
    if value is None and rules.nullable:
        return
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        options = typing.get_args(hint)
        if value is None and type(None) in options:
            return
        (hint,) = [option for option in options if option is not type(None)]
        origin = typing.get_origin(hint)
    if origin is list:
        if not isinstance(value, list):
            raise DataFormatError(f"field '{name}' must be a list, got {value!r:.60}")
        (item_hint,) = typing.get_args(hint)
        for index, item in enumerate(value):
            _check_value(item_hint, item, f"{name}[{index}]", rules)
        return
    if origin is dict:
        if not isinstance(value, dict):
            raise DataFormatError(f"field '{name}' must be an object, got {value!r:.60}")
        key_hint, item_hint = typing.get_args(hint)
        for key, item in value.items():
            _check_scalar(key_hint, key, f"{name} key", rules)
            _check_value(item_hint, item, f"{name}[{key!r:.40}]", rules)
        return
    if dataclasses.is_dataclass(hint):
        check_object(typing.cast(type[Any], hint), value, f"{name}.")
        return
    _check_scalar(hint, value, name, rules)


def _check_scalar(hint: Any, value: Any, name: str, rules: _Rules) -> None:
    if hint is bool:
        if not isinstance(value, bool):
            raise DataFormatError(f"field '{name}' must be true or false, got {value!r:.60}")
        return
    if hint is str:
        if not isinstance(value, str):
            raise DataFormatError(f"field '{name}' must be a string, got {value!r:.60}")
        if rules.non_empty and not value:
            raise DataFormatError(f"field '{name}' must not be empty")
        return
    if hint is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise DataFormatError(f"field '{name}' must be an integer, got {value!r:.60}")
        if abs(value) > MAX_INTEGER:
            raise DataFormatError(
                f"field '{name}' must be at most {MAX_INTEGER}, got {_size(value)}"
            )
    elif hint is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise DataFormatError(f"field '{name}' must be a number, got {value!r:.60}")
        try:
            finite = math.isfinite(value)
        except OverflowError:  # an integer too large for a float (300+ digits)
            finite = False
        if not finite:
            raise DataFormatError(f"field '{name}' must be finite, got {_size(value)}")
    else:
        raise DataFormatError(f"field '{name}' has a type this reader cannot check: {hint!r}")
    if not rules.signed and value < 0:
        raise DataFormatError(f"field '{name}' must be >= 0, got {value!r}")


def _size(value: float) -> str:
    """A number short enough for a message, even one of thousands of digits."""
    if isinstance(value, int) and abs(value) > MAX_INTEGER:
        return f"about 10^{int(abs(value).bit_length() * math.log10(2))}"
    return repr(value)
