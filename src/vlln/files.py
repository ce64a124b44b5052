"""Files: written so that a kill never leaves a half-written one behind, output folders
checked before any work, untrusted files read only up to a cap, and JSON read from untrusted
bytes without a traceback."""

from __future__ import annotations

import gzip
import io
import itertools
import json
import os
import re
import shutil
import tempfile
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from PIL import Image

from vlln.errors import ConfigError, DataFormatError, VllnError, WriteError

T = TypeVar("T")

# Files are written for the user and their collaborators to read, like any other output.
_MODE = 0o644


@contextmanager
def writing(path: Path) -> Iterator[None]:
    """Turn an ``OSError`` of writing ``path`` (a full disk, a read-only folder, no
    permission) into a one-line :class:`WriteError` naming the path and the cause."""
    try:
        yield
    except OSError as error:
        if isinstance(error, VllnError):
            raise
        raise WriteError(
            f"cannot write {path}: {error.strerror or error}; free some space or make the "
            "folder writable, then run the same command again"
        ) from None


def write_bytes_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` through a temporary file in the same folder and a rename: readers see
    the old file or the new one, never a partial one; a failed write is a :class:`WriteError`."""
    with writing(path):
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as handle:
                handle.write(data)
                handle.flush()
                os.fsync(handle.fileno())  # on disk before the rename makes it visible
            os.chmod(temp, _MODE)
            os.replace(temp, path)
        except BaseException:
            Path(temp).unlink(missing_ok=True)
            raise


def remove_leftover_temp_files(folder: Path) -> None:
    """Delete the temporary files that :func:`write_bytes_atomic` leaves when its process is
    killed between writing and renaming; only for a folder that no other process writes."""
    if folder.is_dir():
        for temp in folder.rglob(".*.tmp"):
            if temp.is_file():
                temp.unlink()


def write_text_atomic(path: Path, text: str) -> None:
    """:func:`write_bytes_atomic` for UTF-8 text with Unix line endings."""
    write_bytes_atomic(path, text.encode("utf-8"))


def replace_folder(out: Path, write: Callable[[Path], T], owned: Callable[[Path], bool]) -> T:
    """Run ``write`` into a fresh folder beside ``out``, then put it in ``out``'s place.

    A second run of a command never leaves the first run's files among its own. Only a
    folder whose every entry ``owned`` accepts (files the command itself writes) is
    replaced; a file, or a folder holding anything else, is refused before any work.
    """
    check_output_folder(out)
    if out.is_dir():
        foreign = [entry.name for entry in out.iterdir() if not owned(entry)]
        if foreign:
            raise ConfigError(
                f"--out {out} holds files this command did not write ({', '.join(foreign[:3])}); "
                "give a new folder or an earlier output folder of the same command"
            )
    out.parent.mkdir(parents=True, exist_ok=True)
    fresh = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.", suffix=".new"))
    try:
        result = write(fresh)
        os.chmod(fresh, 0o755)
        if out.is_dir():
            old = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.", suffix=".old"))
            os.replace(out, old / out.name)
            os.replace(fresh, out)
            shutil.rmtree(old)
        else:
            os.replace(fresh, out)
    except BaseException:
        shutil.rmtree(fresh, ignore_errors=True)
        raise
    return result


def check_output_folder(out: Path, option: str = "--out") -> None:
    """Refuse, before any work, an output folder that cannot be written: a file, a path under a
    file, or a place where no file may be made (permissions, a read-only file system). Probes
    by making and removing a temporary folder in ``out`` or its nearest existing parent, so it
    leaves nothing behind."""
    existing = out
    while not os.path.exists(existing) and existing.parent != existing:
        existing = existing.parent
    if not os.path.isdir(existing):
        where = "is a file" if existing == out else f"is under the file {existing}"
        raise ConfigError(f"{option} {out} {where}, not a folder; give a folder path")
    try:
        tempfile.TemporaryDirectory(dir=existing, prefix=".vlln-probe-").cleanup()
    except OSError as error:
        raise ConfigError(
            f"{option} {out}: cannot write in {existing} ({error.strerror}); "
            "give a folder you can write to"
        ) from None


def refuse_other_settings(
    folder: Path, recorded: Mapping[str, Any], wanted: Mapping[str, Any], what: str
) -> None:
    """The one guard of a resumable folder (an evaluation run, a dataset, a web study): going
    on with other settings than the folder was started with would mix two experiments in it,
    so each setting that differs is named and the work refused."""
    changed = [
        name
        for name in sorted(recorded.keys() | wanted.keys())
        if recorded.get(name) != wanted.get(name)
    ]
    if changed:
        values = "; ".join(
            f"{name}: {_short(recorded.get(name))} there, {_short(wanted.get(name))} now"
            for name in changed
        )
        raise ConfigError(
            f"{folder} holds {what} with other settings (differing: {', '.join(changed)}; "
            f"{values}); resume with the same settings, or use another --out"
        )


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


@dataclass(frozen=True)
class ReadCap:
    """The most bytes one kind of input is read to, after decompression: what keeps a gzip
    bomb, ``/dev/zero`` or a wrong file from filling the memory. Where real inputs may be
    larger, ``variable`` names an environment variable that sets the cap in MiB."""

    what: str  # the kind of input, as the error names it
    mib: int
    variable: str | None = None

    def limit(self) -> int:
        """The cap in bytes; a bad value of ``variable`` is a one-line error."""
        text = os.environ.get(self.variable) if self.variable else None
        if text is None:
            return self.mib << 20
        if not text.strip().isdecimal() or int(text) < 1:
            raise ConfigError(f"{self.variable}={text!r}: give a whole number of MiB, 1 or more")
        return int(text) << 20

    def read(self, path: Path, gzipped: bool = False) -> bytes:
        """The bytes of ``path`` (decompressed when ``gzipped``), never more than the cap
        held in memory; over it is a :class:`DataFormatError` naming the cap and its fix.
        Missing files and folders raise ``OSError`` as ``open`` does."""
        limit = self.limit()
        with gzip.open(path, "rb") if gzipped else path.open("rb") as handle:
            data = handle.read(limit + 1)
        if len(data) <= limit:
            return data
        raise self._refusal(path, limit, " after decompression" if gzipped else "")

    def check_size(self, path: Path, size: int | None = None) -> None:
        """Refuse ``path`` when it holds more than the cap, before a library that reads it
        whole (a mesh loader, a table reader) does so; ``size`` is what the read will hold
        when the file does not say it on disk (a table's uncompressed bytes)."""
        limit = self.limit()
        held = path.stat().st_size if size is None else size
        if held > limit:
            raise self._refusal(path, limit, " uncompressed" if size is not None else "")

    def _refusal(self, path: Path, limit: int, after: str) -> DataFormatError:
        fix = (
            f"set {self.variable} to more MiB if the file is right"
            if self.variable
            else "give the right file"
        )
        return DataFormatError(
            f"{path} holds more than {limit >> 20} MiB{after}, the cap on {self.what}; {fix}"
        )


# No image vlln reads has more pixels (its frames are 640 x 480): decoded, an image holds three
# bytes a pixel, and Pillow itself refuses only from 179 million pixels (half a gigabyte) on.
MAX_IMAGE_PIXELS = 4096 * 4096


@contextmanager
def open_image(source: Path | bytes, where: str | Path) -> Iterator[Image.Image]:
    """``source`` opened as an image, not yet decoded (decode it inside the block); a file
    that is no image, or one of more than :data:`MAX_IMAGE_PIXELS`, is a one-line
    :class:`DataFormatError` naming ``where``. A missing file raises ``FileNotFoundError``."""
    try:
        image = Image.open(io.BytesIO(source) if isinstance(source, bytes) else source)
    except FileNotFoundError:
        raise
    except (OSError, ValueError, Image.DecompressionBombError) as error:
        raise DataFormatError(f"{where} is not an image vlln can read: {error}") from None
    with image:
        width, height = image.size
        if width * height > MAX_IMAGE_PIXELS:
            raise DataFormatError(
                f"{where} is a {width} x {height} image, more than the {MAX_IMAGE_PIXELS:,} "
                "pixels of any frame vlln reads; give the dataset's own image"
            )
        yield image


# JSON nested deeper than this is refused: no file vlln reads nests more than a few levels,
# and a deeper value would only overflow the stack of whatever walks it next.
MAX_JSON_DEPTH = 64
# An integer with more digits does not fit in a float (and Python refuses to read 4,300+).
MAX_INTEGER_DIGITS = 308
# A lone UTF-16 surrogate (escaped as \ud800 in JSON, or raw in a str) decodes but can never be
# encoded as UTF-8 again, so every later write of the value would fail: it is refused on reading.
_SURROGATE = re.compile(r"\\u[dD][89a-fA-F]|[\ud800-\udfff]")


def parse_json(
    data: bytes | str, object_hook: Callable[[dict[str, Any]], Any] | None = None
) -> Any:
    """The JSON value of untrusted bytes or text. Anything that is not plain UTF-8 JSON (a
    binary file, a torn write, an integer of hundreds of digits, nesting deeper than
    :data:`MAX_JSON_DEPTH`, text that cannot be written back as UTF-8) is a
    :class:`DataFormatError` with a short reason, never a ``ValueError``, ``OverflowError``,
    ``RecursionError`` or a later ``UnicodeEncodeError``; callers add the file's name.
    ``object_hook`` sees every object as it is decoded, innermost first (``json.loads``)."""
    text = utf8_text(data) if isinstance(data, bytes) else data
    try:
        value = json.loads(text, parse_int=_parse_int, object_hook=object_hook)
    except RecursionError:
        raise DataFormatError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels") from None
    except json.JSONDecodeError as error:
        raise DataFormatError(f"not JSON ({error})") from None
    _check_depth(value)
    if _SURROGATE.search(text):  # rare: only then is every string looked at
        _check_encodable(value)
    return value


def utf8_text(data: bytes) -> str:
    """``data`` decoded as UTF-8; anything else is a :class:`DataFormatError`."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise DataFormatError(f"not UTF-8 text (byte {error.start})") from None


def _parse_int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_INTEGER_DIGITS:
        raise DataFormatError(
            f"an integer of {len(text.lstrip('-'))} digits (at most {MAX_INTEGER_DIGITS})"
        )
    return int(text)


def _check_depth(value: Any) -> None:
    """Refuse nesting deeper than MAX_JSON_DEPTH, without recursion and holding one iterator a
    level (what json.loads returns holds only exact lists and dicts as containers)."""
    levels: list[Iterator[Any]] = [iter((value,))]
    while levels:
        for child in levels[-1]:
            if type(child) is list or type(child) is dict:
                if len(levels) > MAX_JSON_DEPTH:
                    raise DataFormatError(f"JSON nested deeper than {MAX_JSON_DEPTH} levels")
                levels.append(iter(child.values() if type(child) is dict else child))
                break
        else:
            levels.pop()


def _check_encodable(value: Any) -> None:
    """Refuse a string (or key) holding a lone surrogate; a valid pair escaped in JSON decodes
    to one character and passes. Walked as :func:`_check_depth` walks, whose bound on the depth
    bounds the iterators held."""
    levels: list[Iterator[Any]] = [iter((value,))]
    while levels:
        for child in levels[-1]:
            if type(child) is dict or type(child) is list:
                levels.append(
                    itertools.chain(child, child.values()) if type(child) is dict else iter(child)
                )
                break
            if type(child) is str:
                try:
                    child.encode("utf-8")
                except UnicodeEncodeError as error:
                    raise DataFormatError(
                        f"text with a lone UTF-16 surrogate ({child[error.start]!r} at "
                        f"character {error.start}), which is not Unicode text"
                    ) from None
        else:
            levels.pop()
