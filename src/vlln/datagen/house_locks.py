"""Which houses of a dataset folder a build is writing: one lock byte per house.

Two builds writing one house at once would both append to its journal. Shards of a build
write disjoint houses into one folder side by side on purpose, so a build does not lock the
whole folder (as ``vlln eval`` does its run folder): it holds, in the folder's
:data:`LOCK_FILE`, a POSIX record lock on one byte per house seed it builds. A build whose
houses another build holds stops before writing anything, in one line. The kernel drops the
locks when the process ends, however it ends, so a killed build never leaves a stale lock.
"""

from __future__ import annotations

import fcntl
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

from vlln.errors import ConfigError

LOCK_FILE = ".build.lock"


@contextmanager
def lock_houses(root: Path, seeds: Sequence[int], scene_id: Callable[[int], str]) -> Iterator[None]:
    """Hold the houses ``seeds`` of ``root`` for the block, or raise :class:`ConfigError`
    naming the first one another build holds (``scene_id`` names a seed's house)."""
    root.mkdir(parents=True, exist_ok=True)
    with (root / LOCK_FILE).open("ab") as handle:
        for seed in seeds:
            try:
                fcntl.lockf(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB, 1, seed)
            except OSError:  # EACCES or EAGAIN: another process holds the byte
                raise ConfigError(
                    f"another data build is writing {scene_id(seed)} in {root}; wait "
                    "for it to end, or give this build other houses (--shard) or another --out"
                ) from None
        yield
