"""Train/val/test splits of the procedural houses, by house seed.

The paper splits its 90 scenes 61/15/14 (train/val/test) so that no test scene is seen in
training. We split house seeds the same way: a seed's remainder modulo 90 places it in a
block, ``0..60`` train, ``61..75`` val, ``76..89`` test. Every run of 90 consecutive seeds
therefore holds exactly 61/15/14 houses, the split of a seed never depends on how many houses
are built, and no seed belongs to two splits.

The paper's test protocol is a named split too: VL-LN Bench evaluates on 500 test episodes
drawn from its 14 test scenes (paper, Data Statistics). ``--split test500`` plays the same:
the test split's houses, and 500 of their episodes spread evenly over the houses and through
each house's list (the runner's ``spread_over_scenes``), so every run of the protocol plays
the same 500 episodes.
"""

from __future__ import annotations

from itertools import accumulate

from vlln.errors import ConfigError

SPLIT_SIZES: dict[str, int] = {"train": 61, "val": 15, "test": 14}  # houses per 90 seeds
SPLITS: tuple[str, ...] = tuple(SPLIT_SIZES)
SPLIT_CYCLE = sum(SPLIT_SIZES.values())
TEST_PROTOCOL_SPLIT = "test500"
TEST_PROTOCOL_EPISODES = 500
TEST_PROTOCOL_SOURCE = "test"
"""The built-in split whose houses and episodes the protocol draws from."""
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


def source_split(split: str) -> str:
    """The built-in split a split name reads its houses and episodes from."""
    return TEST_PROTOCOL_SOURCE if split == TEST_PROTOCOL_SPLIT else split
