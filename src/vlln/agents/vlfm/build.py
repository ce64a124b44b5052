"""Learn the co-occurrence prior of the VLFM-style agent from the training houses.

``python -m vlln.agents.vlfm.build [--houses N] [--preset mp3d] [--out FILE]`` generates the
first N houses of the ``train`` split (never a val or test house), counts which categories
share a room and which room types hold them, and writes the JSON that
:mod:`vlln.agents.vlfm.prior` reads. The houses follow from their seeds, and the counts are
written sorted and rounded, so the same arguments always write the same bytes.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter, defaultdict
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from vlln.errors import VllnError
from vlln.files import write_text_atomic
from vlln.tasks.splits import SPLIT_SIZES, house_seeds
from vlln.world.generator.presets import DEFAULT_PRESET, generate_preset_house
from vlln.world.model import House

DEFAULT_OUT = Path(__file__).parent / "data" / "cooccurrence.json"
_DIGITS = 4
_MIN_ROOMS = 2  # pairs seen together in fewer rooms are left out (noise)


def cooccurrence(houses: Iterable[House]) -> dict[str, Any]:
    """The prior's tables (``rooms``, ``in_room``, ``together``) counted over ``houses``."""
    rooms: Counter[str] = Counter()
    holding: defaultdict[str, Counter[str]] = defaultdict(Counter)  # category -> room type
    pairs: defaultdict[str, Counter[str]] = defaultdict(Counter)  # target -> seen category
    alone: Counter[str] = Counter()  # rooms holding each category
    for house in houses:
        contents: defaultdict[int, set[str]] = defaultdict(set)
        for instance in house.instances:
            contents[instance.room_id].add(instance.category)
        for room in house.rooms:
            rooms[room.type] += 1
            held = contents.get(room.id, set())
            for category in held:
                holding[category][room.type] += 1
                alone[category] += 1
                for other in held:
                    pairs[other][category] += 1
    in_room = {
        category: {
            room: round(count / rooms[room], _DIGITS) for room, count in sorted(types.items())
        }
        for category, types in sorted(holding.items())
    }
    together = {
        target: {
            seen: round(count / alone[seen], _DIGITS)
            for seen, count in sorted(seen_with.items())
            if count >= _MIN_ROOMS and seen != target
        }
        for target, seen_with in sorted(pairs.items())
    }
    return {"rooms": dict(sorted(rooms.items())), "in_room": in_room, "together": together}


def build(houses: int, preset: str) -> dict[str, Any]:
    """The prior of the first ``houses`` training houses of ``preset``, with its source."""
    seeds = house_seeds("train", houses)
    tables = cooccurrence(generate_preset_house(seed, preset) for seed in seeds)
    source = {"preset": preset, "split": "train", "house_seeds": seeds}
    return {"source": source, **tables}


def write(prior: dict[str, Any], out: Path) -> None:
    """Atomically: the agent reads this file at every start, so a cut-off one must never stay."""
    write_text_atomic(out, json.dumps(prior, indent=None, separators=(",", ":")) + "\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m vlln.agents.vlfm.build", description=__doc__)
    parser.add_argument("--houses", type=int, default=SPLIT_SIZES["train"])
    parser.add_argument("--preset", default=DEFAULT_PRESET)
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    args = parser.parse_args(argv)
    try:
        write(build(args.houses, args.preset), args.out)
    except (VllnError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
