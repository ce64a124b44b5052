"""Episode instructions: IIGN's category-only sentence and IGN's description of one instance.

An IGN instruction is a :class:`Description` in words: the target's category plus constraints
a person can check by looking (an attribute, the room type, a relation word to some instance of
a category). It must single out the target among every instance of the house, and it should
be *short*, since a long list of attributes reads badly and gives away more than the task
needs. Among equally short ones it prefers what a person notices first (colour, then room,
then neighbours, then material, shape and size, texture last); the seeded rng breaks the rest.

The search is a minimum set cover over the target's same-category rivals, each constraint
covering the rivals it rules out. Constraints with the same cover are interchangeable, so only
the cheapest enter the search, and each step branches only on constraints that rule out the
first rival still standing. A target that no description of at most ``max_constraints``
constraints singles out (two identical chairs in one room with the same neighbours) raises
:class:`AmbiguousTargetError`, so that an episode generator can skip it.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from vlln.errors import ConfigError
from vlln.world.model import House, ObjectInstance

FINE_CATEGORY = "fine grained category"  # the scene-summary key, also the instruction_info name
INSTANCE_ATTRIBUTES: tuple[str, ...] = ("color", "material", "texture", "shape", "size")
DESCRIBABLE_ATTRIBUTES: tuple[str, ...] = (*INSTANCE_ATTRIBUTES, FINE_CATEGORY)
ROOM = "room"  # instruction_info name of a room constraint
NEARBY_OBJECTS = "nearby objects"  # instruction_info name of a relation constraint
UNNAMED_ROOM_TYPES = frozenset({"", "other"})  # "in the other" says nothing
DEFAULT_MAX_CONSTRAINTS = 4

# What a person notices first costs least (also the order of instruction_info); a relation
# that names an attribute of its other instance costs one more than a bare one.
_COST = {"color": 0, ROOM: 2, NEARBY_OBJECTS: 4, "material": 6, "shape": 6, "size": 6}
_COST.update({FINE_CATEGORY: 6, "texture": 8})
_INFO_ORDER = tuple(_COST)
_ADJECTIVE_ORDER = ("texture", "size", "shape", "color", "material")  # "small round red wooden"
_MATERIAL_ADJECTIVE = {"wood": "wooden", "plain": "painted", "tile": "tiled", "foliage": "leafy"}
_VERBS = ("Search for", "Find", "Locate", "Go to", "Navigate to", "Walk to")


class AmbiguousTargetError(ConfigError):
    """No short description singles out the requested instance; skip it as a target."""


@dataclass(frozen=True)
class AttributeConstraint:
    """The instance's ``name`` (one of :data:`DESCRIBABLE_ATTRIBUTES`) equals ``value``."""

    name: str
    value: str

    def __post_init__(self) -> None:
        # A value object built per candidate description: it guards itself (pydantic: 3x cost).
        if self.name not in DESCRIBABLE_ATTRIBUTES:
            raise ConfigError(
                f"attribute {self.name!r} cannot describe an instance; use one of "
                f"{list(DESCRIBABLE_ATTRIBUTES)}"
            )
        if not self.value:
            raise ConfigError(f"attribute {self.name!r} needs a value; empty means unknown")


@dataclass(frozen=True)
class RoomConstraint:
    """The instance stands in a room of type ``room_type`` ("in the kitchen")."""

    room_type: str

    def __post_init__(self) -> None:
        # A value object built per candidate description: it guards itself (pydantic: 3x cost).
        if not self.room_type:
            raise ConfigError("a room constraint needs a room type such as 'kitchen'")


@dataclass(frozen=True)
class RelationConstraint:
    """The instance is ``word`` some instance of ``category`` (with ``attribute``, if given)."""

    word: str
    category: str
    attribute: AttributeConstraint | None = None

    def __post_init__(self) -> None:
        # A value object built per candidate description: it guards itself (pydantic: 3x cost).
        if not (self.word and self.category):
            raise ConfigError(
                f"a relation constraint needs a word and a category, got {self.word!r} and "
                f"{self.category!r}"
            )


Constraint = AttributeConstraint | RoomConstraint | RelationConstraint


@dataclass(frozen=True)
class Description:
    """An instance of ``category`` that satisfies every one of ``constraints``."""

    category: str
    constraints: tuple[Constraint, ...] = ()

    def __post_init__(self) -> None:
        # A value object built per candidate description: it guards itself (pydantic: 3x cost).
        if not self.category:
            raise ConfigError("a description needs the category of the instance it describes")

    @property
    def info(self) -> list[str]:
        """The attribute names the description states, each once, most noticeable first."""
        names = {_info_name(c) for c in self.constraints}
        return [name for name in _INFO_ORDER if name in names]


@dataclass(frozen=True)
class FullInstruction:
    """An IGN instruction: its sentence, the attribute names it states, and its description."""

    text: str
    instruction_info: list[str]
    description: Description


def partial_instruction(category: str) -> str:
    """IIGN's category-only instruction, e.g. ``"Search for the chair."``."""
    if not category or category != category.strip():
        raise ConfigError(
            f"category {category!r} must be a non-empty word without surrounding spaces"
        )
    return f"Search for the {category}."


def matches(house: House, instance: ObjectInstance, description: Description) -> bool:
    """Whether ``instance`` of ``house`` satisfies ``description``."""
    return _HouseIndex(house).matches(instance, description)


def matching_instances(house: House, description: Description) -> list[int]:
    """Ids (ascending) of every instance of ``house`` that satisfies ``description``."""
    return _HouseIndex(house).matching(description)


def full_instruction(
    house: House,
    target_id: int,
    rng: np.random.Generator,
    max_constraints: int = DEFAULT_MAX_CONSTRAINTS,
) -> FullInstruction:
    """The shortest instruction that singles out ``target_id``; see :class:`InstructionWriter`.

    Each call indexes the whole house; to write instructions for many targets of one house,
    make one :class:`InstructionWriter` and call it for each.
    """
    return InstructionWriter(house, max_constraints).full_instruction(target_id, rng)


class InstructionWriter:
    """Writes full instructions for the instances of one house, indexing the house once.

    The house is read when the writer is made; make a new writer after changing the house.
    """

    def __init__(self, house: House, max_constraints: int = DEFAULT_MAX_CONSTRAINTS) -> None:
        if isinstance(max_constraints, bool) or not isinstance(max_constraints, int):
            raise ConfigError(f"max_constraints must be an int >= 0, got {max_constraints!r}")
        if max_constraints < 0:
            raise ConfigError(f"max_constraints must be an int >= 0, got {max_constraints}")
        self._index = _HouseIndex(house)
        self._max_constraints = max_constraints
        self._groups: dict[str, _CategoryGroup] = {}

    def full_instruction(self, target_id: int, rng: np.random.Generator) -> FullInstruction:
        """The shortest description of ``target_id`` in words, with its stated attributes.

        Raises :class:`AmbiguousTargetError` when no description of at most
        ``max_constraints`` constraints singles the target out, and :class:`ConfigError` for
        an id the house does not have.
        """
        target = self._index.by_id.get(target_id)
        if target is None:
            raise ConfigError(
                f"house {self._index.house.name!r} has no instance {target_id}; use the id of "
                "one of its instances"
            )
        candidates = self._shortest_descriptions(target)
        description = candidates[int(rng.integers(len(candidates)))]
        found = self._index.matching(description, self._group(target.category).members)
        if found != [target.id]:
            raise RuntimeError(f"description {description} matches {found}, not [{target.id}]")
        return FullInstruction(_sentence(description, rng), description.info, description)

    def _group(self, category: str) -> _CategoryGroup:
        if category not in self._groups:
            self._groups[category] = _CategoryGroup(self._index, category)
        return self._groups[category]

    def _shortest_descriptions(self, target: ObjectInstance) -> list[Description]:
        """Every shortest, cheapest description that only ``target`` satisfies, sorted."""
        group = self._group(target.category)
        position = group.position[target.id]
        rivals = group.everyone & ~(1 << position)
        # Per cover (the rivals a constraint rules out): its cheapest constraints.
        cheapest: dict[int, tuple[int, list[Constraint]]] = {}
        for constraint in group.constraint_sets[position]:
            cover = rivals & ~group.masks[constraint]
            if cover == 0:
                continue
            cost = _cost(constraint)
            best = cheapest.get(cover)
            if best is None or cost < best[0]:
                cheapest[cover] = (cost, [constraint])
            elif cost == best[0]:
                best[1].append(constraint)
        ruled_out = 0
        for cover in cheapest:
            ruled_out |= cover
        if ruled_out != rivals:
            left = rivals & ~ruled_out
            twins = [inst.id for i, inst in enumerate(group.members) if left >> i & 1]
            raise AmbiguousTargetError(
                f"instance {target.id} ({target.category}) of house {self._index.house.name!r} "
                f"cannot be told apart from instances {twins}, which have all its attributes, its "
                "room type and its relations; skip it as an instruction target"
            )
        costs = {cover: cost for cover, (cost, _) in cheapest.items()}
        for size in range(self._max_constraints + 1):
            solutions = _cheapest_covers(rivals, costs, size)
            if solutions:
                break
        else:
            raise AmbiguousTargetError(
                f"instance {target.id} ({target.category}) of house {self._index.house.name!r} "
                f"needs more than {self._max_constraints} constraints to be singled out; skip "
                "it as an instruction target or raise max_constraints"
            )
        combos = {
            tuple(sorted(combo, key=repr))
            for s in solutions
            for combo in itertools.product(*(cheapest[cover][1] for cover in s))
        }
        # repr is a total order free of hash seeds, so the rng picks reproducibly.
        ordered = sorted(combos, key=lambda combo: [repr(c) for c in combo])
        return [Description(target.category, combo) for combo in ordered]


class _HouseIndex:
    """Instances by id, room types by id, and each instance's neighbours with their words."""

    def __init__(self, house: House) -> None:
        self.house = house
        self.by_id = {inst.id: inst for inst in house.instances}
        self.room_types = {room.id: room.type for room in house.rooms}
        self.neighbours: dict[int, list[tuple[str, ObjectInstance]]] = {}
        for rel in house.relations:
            other = self.by_id.get(rel.object)
            if other is not None and rel.subject != rel.object:
                self.neighbours.setdefault(rel.subject, []).append((rel.word, other))

    def matching(
        self, description: Description, among: Iterable[ObjectInstance] | None = None
    ) -> list[int]:
        """Ids of the instances (of the house, or ``among``) that satisfy ``description``."""
        candidates = self.house.instances if among is None else among
        return sorted(i.id for i in candidates if self.matches(i, description))

    def matches(self, instance: ObjectInstance, description: Description) -> bool:
        return instance.category == description.category and all(
            self._satisfies(instance, c) for c in description.constraints
        )

    def _satisfies(self, instance: ObjectInstance, constraint: Constraint) -> bool:
        if isinstance(constraint, AttributeConstraint):
            return _attribute(instance, constraint.name) == constraint.value
        if isinstance(constraint, RoomConstraint):
            return self.room_types.get(instance.room_id) == constraint.room_type
        wanted = constraint.attribute
        return any(
            word == constraint.word
            and other.category == constraint.category
            and (wanted is None or _attribute(other, wanted.name) == wanted.value)
            for word, other in self.neighbours.get(instance.id, ())
        )

    def constraints_of(self, instance: ObjectInstance) -> set[Constraint]:
        """Every constraint a full instruction may use that ``instance`` satisfies."""
        found: set[Constraint] = set()
        for name in DESCRIBABLE_ATTRIBUTES:
            value = _attribute(instance, name)
            if value and not (name == FINE_CATEGORY and value == instance.category):
                found.add(AttributeConstraint(name, value))
        room_type = self.room_types.get(instance.room_id, "")
        if room_type not in UNNAMED_ROOM_TYPES:
            found.add(RoomConstraint(room_type))
        for word, other in self.neighbours.get(instance.id, ()):
            if not word:
                continue
            found.add(RelationConstraint(word, other.category))
            for name in INSTANCE_ATTRIBUTES:
                if value := _attribute(other, name):
                    attribute = AttributeConstraint(name, value)
                    found.add(RelationConstraint(word, other.category, attribute))
        return found


class _CategoryGroup:
    """The instances of one category as bits, their constraints, and who satisfies each."""

    def __init__(self, index: _HouseIndex, category: str) -> None:
        self.members = sorted(index.house.instances_of(category), key=lambda inst: inst.id)
        self.position = {inst.id: i for i, inst in enumerate(self.members)}
        self.everyone = (1 << len(self.members)) - 1
        self.constraint_sets = [index.constraints_of(inst) for inst in self.members]
        self.masks: dict[Constraint, int] = {}
        for i, constraints in enumerate(self.constraint_sets):
            for constraint in constraints:
                self.masks[constraint] = self.masks.get(constraint, 0) | 1 << i


def _cheapest_covers(rivals: int, costs: dict[int, int], size: int) -> list[tuple[int, ...]]:
    """The cheapest sets of ``size`` covers (keys of ``costs``) whose union is ``rivals``.

    Some chosen cover must rule out the lowest rival still standing, so each step branches only
    on those; a branch stops when it already costs more than the best set found, or when even
    the biggest covers could not rule out the rest in time.
    """
    covers = sorted(costs, key=lambda cover: (costs[cover], cover))
    biggest = max((cover.bit_count() for cover in covers), default=0)
    found: set[tuple[int, ...]] = set()
    best = [float("inf")]

    def extend(standing: int, chosen: tuple[int, ...], cost: int, left: int) -> None:
        if cost > best[0]:
            return
        if standing == 0:
            if cost < best[0]:
                best[0] = cost
                found.clear()
            found.add(tuple(sorted(chosen)))
            return
        if standing.bit_count() > left * biggest:
            return
        lowest = standing & -standing
        for cover in covers:
            if cover & lowest:
                extend(standing & ~cover, (*chosen, cover), cost + costs[cover], left - 1)

    extend(rivals, (), 0, size)
    return sorted(found)


def _attribute(instance: ObjectInstance, name: str) -> str:
    if name == FINE_CATEGORY:
        return instance.fine_category
    value: str = getattr(instance.attributes, name)
    return value


def _info_name(constraint: Constraint) -> str:
    if isinstance(constraint, AttributeConstraint):
        return constraint.name
    return ROOM if isinstance(constraint, RoomConstraint) else NEARBY_OBJECTS


def _cost(constraint: Constraint) -> int:
    extra = isinstance(constraint, RelationConstraint) and constraint.attribute is not None
    return _COST[_info_name(constraint)] + int(extra)


# --- words ------------------------------------------------------------------------------


def _adjective(name: str, value: str) -> str:
    if name == "material":
        return _MATERIAL_ADJECTIVE.get(value, value)
    return "medium-sized" if name == "size" and value == "medium" else value


def _noun_phrase(noun: str, attributes: Iterable[AttributeConstraint]) -> str:
    """``noun`` with its adjectives in English order, skipping words it already says."""
    values = {a.name: a.value for a in attributes}
    noun = values.pop(FINE_CATEGORY, noun)
    words: list[str] = []
    for name in _ADJECTIVE_ORDER:
        if name in values:
            adjective = _adjective(name, values[name])
            said = " ".join([*words, noun]).split()
            if not set(adjective.split()) <= set(said):
                words.append(adjective)
    return " ".join([*words, noun])


def _room_phrase(room_type: str) -> str:
    return "on the stairs" if room_type == "stairs" else f"in the {room_type}"


def _relation_phrase(relation: RelationConstraint, own_category: str) -> str:
    attributes = [relation.attribute] if relation.attribute else []
    article = "another" if relation.category == own_category else "the"
    return f"{relation.word} {article} {_noun_phrase(relation.category, attributes)}"


def _sentence(description: Description, rng: np.random.Generator) -> str:
    """One of a few phrasings of ``description``, chosen by ``rng``."""
    constraints = description.constraints
    attributes = [c for c in constraints if isinstance(c, AttributeConstraint)]
    rooms = [_room_phrase(c.room_type) for c in constraints if isinstance(c, RoomConstraint)]
    relations = " and ".join(
        _relation_phrase(c, description.category)
        for c in constraints
        if isinstance(c, RelationConstraint)
    )
    target = "the " + _noun_phrase(description.category, attributes)
    room = " and ".join(rooms)
    verb = _VERBS[int(rng.integers(len(_VERBS)))]
    forms = [[verb, target, room, relations]]
    if room and relations:
        forms.append([verb, target, relations, room])
        forms.append([verb, target, "that is " + relations, room])
    if room:
        forms.append([room[0].upper() + room[1:] + ",", verb.lower(), target, relations])
    form = forms[int(rng.integers(len(forms)))]
    return " ".join(part for part in form if part) + "."
