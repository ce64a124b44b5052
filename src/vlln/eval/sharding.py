"""Splitting one evaluation into independent shards: ``--shard i/n`` keeps every episode whose
index (in the run's fixed episode order) is ``i`` mod ``n``.

The rule needs nothing but the two numbers, so it works under any launcher (a shell loop,
SLURM array jobs, Ray tasks); shards write separate run directories and ``vlln score`` merges
them. Round-robin rather than contiguous blocks spreads slow houses over all shards.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

from vlln.errors import ConfigError

T = TypeVar("T")
_SHARD = re.compile(r"^\s*(\d+)\s*/\s*(\d+)\s*$")


@dataclass(frozen=True)
class Shard:
    """Shard ``index`` of ``count`` (0-based)."""

    index: int
    count: int

    def __post_init__(self) -> None:
        # A flag's value (``--shard i/n``): as a pydantic dataclass the generated command line
        # would expand it into nested flags, so it stays a plain dataclass that guards itself.
        if self.count < 1 or not 0 <= self.index < self.count:
            raise ConfigError(
                f"shard {self.index}/{self.count} does not exist; write i/n with 0 <= i < n, "
                "e.g. 0/4 for the first of four shards"
            )

    @staticmethod
    def parse(text: str) -> Shard:
        """``"1/4"`` -> Shard(1, 4)."""
        match = _SHARD.match(text)
        if match is None:
            raise ConfigError(f"cannot read shard {text!r}; write i/n, e.g. 0/4")
        return Shard(int(match.group(1)), int(match.group(2)))

    def take(self, items: Sequence[T]) -> list[T]:
        """The items whose index is ``index`` mod ``count``, in their order."""
        return [item for position, item in enumerate(items) if position % self.count == self.index]

    def __str__(self) -> str:
        return f"{self.index}/{self.count}"
