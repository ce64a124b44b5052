"""Tests of the train/val/test split of house seeds."""

from __future__ import annotations

from collections import Counter
from typing import Any

import pytest

from vlln.errors import ConfigError
from vlln.tasks.splits import SPLITS, house_seeds, split_of


@pytest.mark.parametrize("first", [0, 90, 1234])
def test_every_90_consecutive_seeds_split_61_15_14(first: int) -> None:
    counts = Counter(split_of(seed) for seed in range(first, first + 90))
    assert counts == {"train": 61, "val": 15, "test": 14}


def test_house_seeds_are_the_first_seeds_of_their_split() -> None:
    for split in SPLITS:
        seeds = house_seeds(split, 40)
        assert seeds == [s for s in range(1000) if split_of(s) == split][:40]
        assert house_seeds(split, 7) == seeds[:7]


def test_splits_never_share_a_seed() -> None:
    chosen = {split: set(house_seeds(split, 200)) for split in SPLITS}
    assert not chosen["train"] & chosen["test"]
    assert not chosen["train"] & chosen["val"]
    assert not chosen["val"] & chosen["test"]
    assert all(split_of(seed) == split for split, seeds in chosen.items() for seed in seeds)


def test_zero_houses_is_an_empty_list() -> None:
    assert house_seeds("test", 0) == []


@pytest.mark.parametrize("seed", [-1, True, 2.0])
def test_a_bad_seed_is_a_config_error(seed: Any) -> None:
    with pytest.raises(ConfigError, match="seed"):
        split_of(seed)


def test_a_bad_split_or_count_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match="unknown split 'dev'"):
        house_seeds("dev", 3)
    with pytest.raises(ConfigError, match="count"):
        house_seeds("train", -1)
