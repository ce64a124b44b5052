"""Checked reading of JSON fields: each reader returns the typed value or raises
:class:`FieldError` naming the field at fault, which the file's reader turns into one line
with the file and the record (:mod:`vlln.tasks.episode`)."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from vlln.world.model import Point3


class Absent:
    """The value of a key that is missing (shown as such in an error)."""

    def __repr__(self) -> str:
        return "no such key"


class FieldError(Exception):
    """A field that does not follow the format; turned into a DataFormatError with context."""

    def __init__(self, field: str, expected: str, got: Any) -> None:
        super().__init__(field)
        self.field, self.expected, self.got = field, expected, got


def check_keys(
    data: Any,
    name: str,
    required: tuple[str, ...],
    optional: tuple[str, ...] = (),
    ignored: tuple[str, ...] = (),
) -> dict[str, Any]:
    """``data`` as an object holding every ``required`` key and no key outside ``required``,
    ``optional`` and ``ignored`` (keys the reference writes that nothing reads)."""
    if not isinstance(data, dict):
        raise FieldError(name or "episode", "a JSON object", data)
    prefix = f"{name}." if name else ""
    unknown = sorted(set(data) - set(required) - set(optional) - set(ignored))
    if unknown:
        raise FieldError(
            prefix + unknown[0], f"only the keys {[*required, *optional]}", data[unknown[0]]
        )
    for key in required:
        if key not in data:
            raise FieldError(prefix + key, "a value", Absent())
    return data


def text_of(value: Any, name: str) -> str:
    if not isinstance(value, str):
        raise FieldError(name, "a string", value)
    return value


def numbers_of(value: Any, name: str, count: int) -> tuple[float, ...]:
    if not (
        isinstance(value, list)
        and len(value) == count
        and all(
            isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
            for v in value
        )
    ):
        raise FieldError(name, f"a list of {count} finite numbers", value)
    return tuple(float(v) for v in value)


def point_of(value: Any, name: str) -> Point3:
    x, y, z = numbers_of(value, name, 3)
    return (x, y, z)


def texts_of(value: Any, name: str) -> tuple[str, ...]:
    if not isinstance(value, list):
        raise FieldError(name, "a list of strings", value)
    return tuple(text_of(v, f"{name}[{i}]") for i, v in enumerate(value))


def id_text_of(value: Any, name: str) -> str:
    """An id written as a string or an integer (hand-made and Habitat files use both)."""
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value)
    if not isinstance(value, str):
        raise FieldError(name, "a string or an integer", value)
    return value


def shown(value: Any, width: int = 80) -> str:
    """``repr(value)`` cut to ``width`` characters, a cut one ending in "...", written no further
    than that: the whole repr of a hostile value could take several times its memory."""
    pieces: list[str] = []
    length = 0
    for piece in _repr_pieces(value, width):
        pieces.append(piece)
        length += len(piece)
        if length > width:
            break
    text = "".join(pieces)
    return text if len(text) <= width else text[: width - 3] + "..."


def _repr_pieces(value: Any, width: int) -> Iterator[str]:
    """The repr of a JSON value piece by piece, a long string only in part."""
    if type(value) is list:
        yield "["
        for index, item in enumerate(value):
            yield ", " if index else ""
            yield from _repr_pieces(item, width)
        yield "]"
    elif type(value) is dict:
        yield "{"
        for index, (key, item) in enumerate(value.items()):
            yield ", " if index else ""
            yield from _repr_pieces(key, width)
            yield ": "
            yield from _repr_pieces(item, width)
        yield "}"
    elif type(value) is str and len(value) > width:
        # A quote of each kind the text holds, after the part shown: repr picks the same quotes.
        yield repr(value[:width] + "'" * ("'" in value) + '"' * ('"' in value))
    else:
        yield repr(value)
