"""The paper's test protocol as a named split: 500 episodes on the 14 test houses.

VL-LN Bench evaluates on 500 test episodes drawn from its 14 test scenes (paper, Data
Statistics). ``--split test500`` plays the same: the test split's houses, and 500 of their
episodes spread evenly over the houses and through each house's list (the runner's
``spread_over_scenes``), so every run of the protocol plays the same 500 episodes.
"""

from __future__ import annotations

TEST_PROTOCOL_SPLIT = "test500"
TEST_PROTOCOL_EPISODES = 500
TEST_PROTOCOL_SOURCE = "test"
"""The built-in split whose houses and episodes the protocol draws from."""


def source_split(split: str) -> str:
    """The built-in split a split name reads its houses and episodes from."""
    return TEST_PROTOCOL_SOURCE if split == TEST_PROTOCOL_SPLIT else split
