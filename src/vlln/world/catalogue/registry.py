"""The catalogue: categories by name, assembled explicitly from the category modules."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterator
from functools import cache

from vlln.errors import UnknownCategoryError
from vlln.world.catalogue.base import Category

ROOM_TYPES: tuple[str, ...] = (
    "living room",
    "bedroom",
    "kitchen",
    "dining room",
    "bathroom",
    "toilet",
    "study",
    "corridor",
    "storage room",
    "gym",
)


class Catalogue:
    """A fixed set of categories, looked up by name."""

    def __init__(self, categories: list[Category]) -> None:
        self._by_name: dict[str, Category] = {}
        for category in categories:
            if category.name in self._by_name:
                raise ValueError(f"category {category.name!r} is defined twice")
            self._by_name[category.name] = category

    @property
    def names(self) -> list[str]:
        return sorted(self._by_name)

    def __len__(self) -> int:
        return len(self._by_name)

    def __iter__(self) -> Iterator[Category]:
        return iter(self._by_name[name] for name in self.names)

    def get(self, name: str) -> Category:
        try:
            return self._by_name[name]
        except KeyError:
            raise UnknownCategoryError(
                f"unknown object category {name!r}; the catalogue has {len(self)}: "
                f"{', '.join(self.names)}"
            ) from None

    def for_room(self, room_type: str) -> list[Category]:
        """Categories that can appear in a room of this type, in name order."""
        return [c for c in self if room_type in c.rooms]

    def fingerprint(self) -> str:
        """A short hash of every category's words, placement and rooms.

        Seeded houses change with the catalogue, so files built from them (cached episode
        splits) record it and are rebuilt when it differs.
        """
        described = [
            [c.name, c.shapes, c.colors, c.materials, c.placement.value, c.rooms, c.wall_height]
            for c in self
        ]
        text = json.dumps(described, sort_keys=True)
        return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


@cache
def default_catalogue() -> Catalogue:
    """Every built-in category."""
    from vlln.world.catalogue import (
        bathroom,
        bedroom,
        decor,
        electronics,
        gadgets,
        groceries,
        household,
        keepsakes,
        kitchen,
        kitchenware,
        misc,
        personal,
        seating,
        stationery,
        storage,
        tables,
        tableware,
        toiletries,
    )

    modules = (
        seating,
        tables,
        storage,
        bedroom,
        bathroom,
        kitchen,
        electronics,
        decor,
        tableware,
        misc,
        personal,
        toiletries,
        kitchenware,
        groceries,
        household,
        gadgets,
        keepsakes,
        stationery,
    )
    return Catalogue([c for module in modules for c in module.CATEGORIES])
