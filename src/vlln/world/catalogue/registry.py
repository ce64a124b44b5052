"""The catalogue: categories by name, assembled explicitly from the category modules."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterator
from functools import cache

from vlln.errors import UnknownCategoryError
from vlln.world.catalogue.aliases import ALIASES, canonical_category
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
    """A fixed set of categories, looked up by name or by an alias (see :mod:`.aliases`)."""

    def __init__(self, categories: list[Category]) -> None:
        self._by_name: dict[str, Category] = {}
        for category in categories:
            if category.name in self._by_name or category.name in ALIASES:
                raise ValueError(f"category {category.name!r} is defined twice or is an alias")
            self._by_name[category.name] = category

    @property
    def names(self) -> list[str]:
        return sorted(self._by_name)

    def __len__(self) -> int:
        return len(self._by_name)

    def __iter__(self) -> Iterator[Category]:
        return iter(self._by_name[name] for name in self.names)

    @property
    def aliases(self) -> dict[str, str]:
        """Alias -> category name, for the aliases of categories this catalogue has."""
        return {alias: name for alias, name in ALIASES.items() if name in self._by_name}

    def get(self, name: str) -> Category:
        """The category called ``name`` or that ``name`` is an alias of."""
        try:
            return self._by_name[canonical_category(name)]
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
        appliances,
        bathroom,
        bedroom,
        cleaning,
        decor,
        electronics,
        fixtures,
        gadgets,
        groceries,
        household,
        keepsakes,
        kitchen,
        kitchenware,
        leisure,
        misc,
        personal,
        seating,
        stationery,
        storage,
        tables,
        tableware,
        textiles,
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
        appliances,
        household,
        textiles,
        fixtures,
        leisure,
        personal,
        toiletries,
        kitchenware,
        groceries,
        cleaning,
        gadgets,
        keepsakes,
        stationery,
    )
    return Catalogue([c for module in modules for c in module.CATEGORIES])
