"""Which trajectories a balanced dataset keeps: at most ``per_scene`` of each scene and
``per_category`` of each target category.

The paper filters its 41,891 IIGN trajectories to 11,661 "with balanced scenes and target
categories" (docs/reference-facts.md §5) without stating the rule; this is ours. Both caps
default to the median count (of the scenes, of the categories), so the crowded half is cut
down to the typical one and the sparse half is kept whole. The categories take turns, rarest
first, each taking one trajectory per round, from the scene that has the fewest kept so far
and still has room (among equals, in an order drawn from the seed), until none can take
more: every category gets its share before a crowded one fills a scene's cap, the scenes
fill evenly, and the same dataset, caps and seed always select the same set.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass
from typing import Annotated

import numpy as np
from pydantic import Field

from vlln.config import Config


class BalanceConfig(Config):
    """How a dataset is balanced; recorded in the balanced dataset's ``build.json``."""

    seed: Annotated[int, Field(ge=0)] = 0
    """seed of the order in which equally rare trajectories are taken"""
    per_scene: Annotated[int | None, Field(ge=1)] = None
    """most trajectories kept per scene (none: the median count of the scenes)"""
    per_category: Annotated[int | None, Field(ge=1)] = None
    """most trajectories kept per target category (none: the median count of the categories)"""


@dataclass(frozen=True)
class Item:
    """One trajectory of the dataset: where it is and what it is counted by."""

    house: str  # house folder name
    episode_index: int
    scene: str
    category: str


@dataclass(frozen=True)
class Selection:
    """The kept trajectories and the counts before and after (every scene and category of
    the dataset appears in both, with 0 where nothing was kept)."""

    kept: list[Item]
    per_scene: int
    per_category: int
    scenes_before: dict[str, int]
    scenes_after: dict[str, int]
    categories_before: dict[str, int]
    categories_after: dict[str, int]


def median_cap(counts: Counter[str]) -> int:
    """The median of the counts, rounded up (at least 1)."""
    return max(1, math.ceil(float(np.median(list(counts.values()))))) if counts else 1


def select(items: list[Item], config: BalanceConfig) -> Selection:
    """The balanced subset of ``items`` (in the items' order)."""
    scenes = Counter(item.scene for item in items)
    categories = Counter(item.category for item in items)
    per_scene = config.per_scene or median_cap(scenes)
    per_category = config.per_category or median_cap(categories)
    draw = np.random.default_rng(np.random.SeedSequence([config.seed, 17])).permutation(len(items))
    pools: dict[str, list[int]] = {}
    for i in sorted(range(len(items)), key=lambda i: int(draw[i])):
        pools.setdefault(items[i].category, []).append(i)
    scene_kept: Counter[str] = Counter()
    category_kept: Counter[str] = Counter()
    chosen: set[int] = set()
    turns = sorted(pools, key=lambda name: (categories[name], name))
    while turns:
        again = []
        for name in turns:
            pool = pools[name]
            room = [i for i in pool if scene_kept[items[i].scene] < per_scene]
            if not room:
                continue
            pick = min(room, key=lambda i: scene_kept[items[i].scene])  # first in draw order
            pool.remove(pick)
            chosen.add(pick)
            scene_kept[items[pick].scene] += 1
            category_kept[name] += 1
            if category_kept[name] < per_category and pool:
                again.append(name)
        turns = again
    return Selection(
        kept=[item for i, item in enumerate(items) if i in chosen],
        per_scene=per_scene,
        per_category=per_category,
        scenes_before=dict(sorted(scenes.items())),
        scenes_after={name: scene_kept[name] for name in sorted(scenes)},
        categories_before=dict(sorted(categories.items())),
        categories_after={name: category_kept[name] for name in sorted(categories)},
    )


@dataclass(frozen=True)
class Flatness:
    """How evenly counts are spread: Gini coefficient (0: all equal) and max / mean."""

    gini: float
    max_over_mean: float


def flatness(counts: dict[str, int]) -> Flatness:
    """The flatness of a histogram (its zero bins included)."""
    values = np.sort(np.array(list(counts.values()), np.float64))
    if values.size == 0 or values.sum() == 0.0:
        return Flatness(0.0, 0.0)
    n = values.size
    ranks = np.arange(1, n + 1)
    gini = float((2.0 * ranks - n - 1.0) @ values / (n * values.sum()))
    return Flatness(gini, float(values.max() / values.mean()))
