"""Writing files so that a kill never leaves a half-written one behind."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from vlln.errors import ConfigError

T = TypeVar("T")

# Files are written for the user and their collaborators to read, like any other output.
_MODE = 0o644


def write_bytes_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` through a temporary file in the same folder and a rename: readers see
    the old file or the new one, never a partial one."""
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
    if out.exists() and not out.is_dir():
        raise ConfigError(
            f"--out {out} is a file, not a folder; give a new or earlier output folder"
        )
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
