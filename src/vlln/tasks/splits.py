"""Train/val/test splits of the procedural houses, by house seed.

The paper splits its 90 scenes 61/15/14 (train/val/test) so that no test scene is seen in
training. We split house seeds the same way: a seed's remainder modulo 90 places it in a
block, ``0..60`` train, ``61..75`` val, ``76..89`` test. Every run of 90 consecutive seeds
therefore holds exactly 61/15/14 houses, the split of a seed never depends on how many houses
are built, and no seed belongs to two splits.
"""

from __future__ import annotations

from itertools import accumulate

from vlln.errors import ConfigError

SPLIT_SIZES: dict[str, int] = {"train": 61, "val": 15, "test": 14}  # houses per 90 seeds
SPLITS: tuple[str, ...] = tuple(SPLIT_SIZES)
SPLIT_CYCLE = sum(SPLIT_SIZES.values())
_FIRST_REMAINDER = dict(zip(SPLITS, accumulate(SPLIT_SIZES.values(), initial=0), strict=False))


def split_block(split: str) -> tuple[int, int]:
    """``[first, last + 1)`` of the seed remainders modulo 90 that belong to ``split``."""
    if split not in SPLIT_SIZES:
        raise ConfigError(f"unknown split {split!r}; choose one of: {', '.join(SPLITS)}")
    first = _FIRST_REMAINDER[split]
    return first, first + SPLIT_SIZES[split]


def split_of(seed: int) -> str:
    """The split (``"train"``, ``"val"`` or ``"test"``) that house ``seed`` belongs to."""
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ConfigError(f"a house seed is a whole number >= 0, got {seed!r}")
    remainder = seed % SPLIT_CYCLE
    return next(split for split in SPLITS if remainder < split_block(split)[1])


def house_seeds(split: str, count: int) -> list[int]:
    """The ``count`` smallest house seeds of ``split``, ascending."""
    first, end = split_block(split)
    if isinstance(count, bool) or not isinstance(count, int) or count < 0:
        raise ConfigError(f"count must be a whole number >= 0, got {count!r}")
    size = end - first
    return [(i // size) * SPLIT_CYCLE + first + i % size for i in range(count)]
